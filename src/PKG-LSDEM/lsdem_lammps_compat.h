/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   The one place where LSDEM meets the differences between the LAMMPS versions it builds
   against: 29 Sep 2021 (Debian bookworm, the default) and 4 Feb 2025 (Debian trixie).
   The styles call these helpers instead of the version-specific LAMMPS API; no other file
   tests the LAMMPS version except through the macros defined here.

   LSDEM_LAMMPS_VERSION (YYYYMMDD of the LAMMPS release) comes from lsdem_lammps_version.h,
   which LSDEM's CMakeLists.txt writes from the tree's src/version.h; without it (another
   build system) the header tells the two supported versions apart by the LAMMPS headers
   present (fix_store.h is gone from 2025's). Compiles as C++11 and C++17.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_LAMMPS_COMPAT_H
#define LMP_LSDEM_LAMMPS_COMPAT_H

#if !defined(LSDEM_LAMMPS_VERSION) && defined(__has_include)
#if __has_include("lsdem_lammps_version.h")
#include "lsdem_lammps_version.h"
#elif !__has_include("fix_store.h")
#define LSDEM_LAMMPS_VERSION 20250204
#endif
#endif
#ifndef LSDEM_LAMMPS_VERSION
#define LSDEM_LAMMPS_VERSION 20210929
#endif

// 1: the API of LAMMPS since 2022 (std::string fields and names, Comm::forward_comm(Fix *),
// Neighbor::add_request, fix STORE/ATOM); 0: the 29 Sep 2021 API
#if LSDEM_LAMMPS_VERSION >= 20220000
#define LSDEM_LAMMPS_NEW_API 1
#else
#define LSDEM_LAMMPS_NEW_API 0
#endif

// 1 when LAMMPS reads Atoms/Velocities lines as char ** into the line buffer and checks
// only the section's first line for its word count (2021): then atom_style lsdem checks
// every line itself. LAMMPS 2025 checks every line (its "Incorrect format in ..." error).
#define LSDEM_CHECK_DATA_LINES (!LSDEM_LAMMPS_NEW_API)

// AtomVec::data_atom(double *coord, imageint image, <these>): the parameters after the
// image flags, declared and passed on to AtomVec::data_atom
#if LSDEM_LAMMPS_NEW_API
#define LSDEM_DATA_ATOM_VALUES const std::vector<std::string> &values, std::string &extract
#define LSDEM_DATA_ATOM_PASS values, extract
#else
#define LSDEM_DATA_ATOM_VALUES char **values
#define LSDEM_DATA_ATOM_PASS values
#endif

#include "atom.h"
#include "comm.h"
#include "neighbor.h"
#include "tokenizer.h"

#include <string>
#include <vector>

#if LSDEM_LAMMPS_NEW_API
#include "fix_store_atom.h"
#else
#include "fix_store.h"
#include "neigh_request.h"
#endif

namespace LAMMPS_NS {
namespace LsdemCompat {

// the LAMMPS release as "4 Feb 2025"-style text is LAMMPS_VERSION (version.h); this is
// the number the build selected
constexpr int lammps_version = LSDEM_LAMMPS_VERSION;

inline const char *cstr(const char *s) { return s; }
inline const char *cstr(const std::string &s) { return s.c_str(); }

#if LSDEM_LAMMPS_NEW_API

// AtomVec::fields_* from a blank-separated list of per-atom names
inline std::vector<std::string> fields(const char *list) { return Tokenizer(list).as_vector(); }
// the name argument of AtomVec::property_atom
typedef const std::string &PropertyName;
inline int peratom_count(const Atom *atom) { return (int) atom->peratom.size(); }

inline void forward_comm(Comm *comm, Fix *fix, int size = 0) { comm->forward_comm(fix, size); }
inline void reverse_comm(Comm *comm, Fix *fix, int size = 0) { comm->reverse_comm(fix, size); }
inline void forward_comm(Comm *comm, Pair *pair) { comm->forward_comm(pair); }
inline void reverse_comm(Comm *comm, Pair *pair) { comm->reverse_comm(pair); }

// a plain full neighbour list for a pair style (instance_me: the pair's own, protected)
inline void request_full_list(Neighbor *neighbor, Pair *pair, int /*instance_me*/)
{
  neighbor->add_request(pair, NeighConst::REQ_FULL);
}

// per-atom storage that migrates with the atoms and goes into restart files
typedef FixStoreAtom FixStorePeratom;
inline std::string fix_store_peratom_args(int ncols)
{
  return "STORE/ATOM " + std::to_string(ncols) + " 0 0 1";
}

#else

inline char *fields(const char *list) { return const_cast<char *>(list); }
typedef char *PropertyName;
inline int peratom_count(const Atom *atom) { return atom->nperatom; }

inline void forward_comm(Comm *comm, Fix *fix, int size = 0) { comm->forward_comm_fix(fix, size); }
inline void reverse_comm(Comm *comm, Fix *fix, int size = 0) { comm->reverse_comm_fix(fix, size); }
inline void forward_comm(Comm *comm, Pair *pair) { comm->forward_comm_pair(pair); }
inline void reverse_comm(Comm *comm, Pair *pair) { comm->reverse_comm_pair(pair); }

inline void request_full_list(Neighbor *neighbor, Pair *pair, int instance_me)
{
  int irequest = neighbor->request(pair, instance_me);
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
}

typedef FixStore FixStorePeratom;
inline std::string fix_store_peratom_args(int ncols)
{
  return "STORE peratom 1 " + std::to_string(ncols);
}

#endif

}    // namespace LsdemCompat
}    // namespace LAMMPS_NS

#endif
