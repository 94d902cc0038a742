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
#include "modify.h"
#include "neighbor.h"
#include "tokenizer.h"

#include <string>
#include <vector>

#include "neigh_request.h"
#if LSDEM_LAMMPS_NEW_API
#include "fix_store_atom.h"
#else
#include "fix_store.h"
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

// a full neighbour list for a compute, built only when it asks (Neighbor::build_one), out
// to cutoff (distance between centres, the skin included)
inline void request_occasional_full_list(Neighbor *neighbor, Compute *compute,
                                         int /*instance_me*/, double cutoff)
{
  neighbor->add_request(compute, NeighConst::REQ_FULL | NeighConst::REQ_OCCASIONAL)
      ->set_cutoff(cutoff);
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

inline void request_occasional_full_list(Neighbor *neighbor, Compute *compute, int instance_me,
                                         double cutoff)
{
  NeighRequest *req = neighbor->requests[neighbor->request(compute, instance_me)];
  req->pair = 0;
  req->compute = 1;
  req->half = 0;
  req->full = 1;
  req->occasional = 1;
  req->cut = 1;
  req->cutoff = cutoff;
}

typedef FixStore FixStorePeratom;
inline std::string fix_store_peratom_args(int ncols)
{
  return "STORE peratom 1 " + std::to_string(ncols);
}

#endif

// a per-atom store of ncols doubles for the atoms of a group, added to modify under id
inline FixStorePeratom *add_peratom_store(Modify *modify, const std::string &id,
                                          const std::string &group, int ncols)
{
  return dynamic_cast<FixStorePeratom *>(
      modify->add_fix(id + " " + group + " " + fix_store_peratom_args(ncols)));
}

// the store added under id, or nullptr (a style looks it up again in init(): the fix
// array may have been rearranged since)
inline FixStorePeratom *find_peratom_store(Modify *modify, const char *id)
{
  const int ifix = modify->find_fix(id);
  return ifix < 0 ? nullptr : dynamic_cast<FixStorePeratom *>(modify->fix[ifix]);
}

}    // namespace LsdemCompat
}    // namespace LAMMPS_NS

#endif
