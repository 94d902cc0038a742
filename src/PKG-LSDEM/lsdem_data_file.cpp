// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: a read_data file's Atoms count against its Atoms lines
   (lsdem_data_file.h). The file is read as read_data reads it: the title line, header
   lines up to the Atoms keyword (text after '#' is a comment), the line after the keyword
   skipped, then the declared number of lines.
------------------------------------------------------------------------- */

#include "lsdem_data_file.h"

#include "fmt/format.h"
#include "utils.h"

#include <cctype>
#include <fstream>
#include <sstream>

using namespace LAMMPS_NS;

namespace {

// the line without its '#' comment, trimmed
std::string content(const std::string &line)
{
  return utils::trim(line.substr(0, line.find('#')));
}

// the N of a header line "N atoms", or -1
long long atoms_declared(const std::string &text)
{
  std::istringstream in(text);
  long long n;
  std::string word;
  return (in >> n >> word) && word == "atoms" && n >= 0 ? n : -1;
}

// what ends the Atoms lines: a blank line (0) or a section keyword (1); an Atoms line (2)
int line_kind(const std::string &line)
{
  const std::string c = utils::trim(line);
  if (c.empty()) return 0;
  return std::isalpha((unsigned char) c[0]) ? 1 : 2;
}

// "N lines (lines A-B)", "1 line (line A)" or "no lines"
std::string line_range(long first, long long count)
{
  if (count == 0) return "no lines";
  if (count == 1) return fmt::format("1 line (line {})", first);
  return fmt::format("{} lines (lines {}-{})", count, first, first + count - 1);
}

// the data file, line by line, counting lines
struct Lines {
  std::ifstream in;
  std::string line;
  long number = 0;    // of `line`
  explicit Lines(const std::string &path) : in(path) {}
  bool next()
  {
    if (!std::getline(in, line)) return false;
    number++;
    return true;
  }
};

// the header's atoms count, or -1; f is left on the line before the first Atoms line (the
// one after the keyword, which read_data skips)
long long read_header(Lines &f)
{
  long long declared = -1;
  if (!f.next()) return -1;    // the title
  while (f.next()) {
    const std::string c = content(f.line);
    if (c == "Atoms") return f.next() ? declared : -1;
    if (declared < 0) declared = atoms_declared(c);
  }
  return -1;
}

// how the Atoms lines end when a blank line (at f.number) cut them: " at the end of the
// file", ": line L is blank, and Atoms lines go on at line L2" or the section after it
std::string after_blank(Lines &f, std::string &fix)
{
  const long blank = f.number;
  while (f.next())
    if (!content(f.line).empty()) break;
  if (f.number == blank || content(f.line).empty()) return " at the end of the file";
  if (line_kind(f.line) == 1)
    return fmt::format(": line {} starts section '{}'", f.number, content(f.line));
  fix = fmt::format("remove the blank line{} (an Atoms section has none)",
                    blank + 1 == f.number ? "" : "s");
  return fmt::format(": line {} is blank, and Atoms lines go on at line {}", blank, f.number);
}

}    // namespace

std::string LsdemDataFile::atoms_count_problem(const std::string &path)
{
  Lines f(path);
  const long long declared = read_header(f);
  if (declared < 0) return "";
  const long first = f.number + 1;
  long long found = 0;
  int kind = 2;
  while (found < declared && f.next() && (kind = line_kind(f.line)) == 2) found++;
  if (found == declared) return "";

  const long long missing = declared - found;
  std::string fix = fmt::format("fix the atoms count in the header or add the {} missing "
                                "Atoms line{}", missing, missing == 1 ? "" : "s");
  std::string end = " at the end of the file";
  if (kind == 0) end = after_blank(f, fix);
  if (kind == 1) end = fmt::format(": line {} starts section '{}'", f.number, content(f.line));
  return fmt::format("read_data: data file {}: the header declares {} atoms but the Atoms "
                     "section ends after {}{}; {}", path, declared, line_range(first, found),
                     end, fix);
}
