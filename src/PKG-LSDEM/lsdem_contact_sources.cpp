/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemContactSources, lsdem_gather_sorted (lsdem_contact_sources.h).
------------------------------------------------------------------------- */

#include "lsdem_contact_sources.h"

#include "error.h"
#include "fix_wall_lsdem.h"
#include "force.h"
#include "modify.h"
#include "pair_lsdem.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

void LsdemContactSources::find(LAMMPS *lmp, const std::vector<std::string> &wall_ids,
                               const char *who)
{
  pair = PairLsdem::of(lmp->force);
  walls.clear();
  for (const auto &wid : wall_ids) {
    const int ifix = lmp->modify->find_fix(wid);
    FixWallLsdem *w =
        ifix < 0 ? nullptr : dynamic_cast<FixWallLsdem *>(lmp->modify->fix[ifix]);
    if (!w) lmp->error->all(FLERR, "{}: {} is not a fix wall/lsdem", who, wid);
    walls.push_back(w);
  }
}

void LsdemContactSources::check_current(LAMMPS *lmp, const char *who) const
{
  const bigint step = lmp->update->ntimestep;
  if (pair && pair->contacts_step() != step)
    lmp->error->all(FLERR, "{} needs pair lsdem forces of step {} (it has {})", who, step,
                    pair->contacts_step());
  for (const FixWallLsdem *w : walls)
    if (w->contacts_step() != step)
      lmp->error->all(FLERR, "{} needs wall forces of step {} from fix {}: define it after "
                      "the walls", who, step, w->id);
}

std::vector<double> LAMMPS_NS::lsdem_gather_sorted(MPI_Comm comm, const std::vector<double> &mine,
                                                   int width)
{
  int me, nprocs;
  MPI_Comm_rank(comm, &me);
  MPI_Comm_size(comm, &nprocs);
  const int n = (int) mine.size();
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  int total = 0;
  for (int p = 0; p < nprocs; p++) displs[p] = total, total += counts[p];
  std::vector<double> all(me == 0 ? total : 0);
  MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              0, comm);
  if (me != 0) return all;
  const int rows = total / width;
  std::vector<int> order(rows);
  for (int r = 0; r < rows; r++) order[r] = r;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::lexicographical_compare(&all[(size_t) a * width], &all[(size_t) (a + 1) * width],
                                        &all[(size_t) b * width], &all[(size_t) (b + 1) * width]);
  });
  std::vector<double> sorted;
  sorted.reserve(all.size());
  for (int r : order)
    sorted.insert(sorted.end(), &all[(size_t) r * width], &all[(size_t) (r + 1) * width]);
  return sorted;
}
