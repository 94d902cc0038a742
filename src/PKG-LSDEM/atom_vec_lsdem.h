/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   atom_style lsdem: one atom per rigid grain. The grain's shape is an index into a
   memory-mapped shape library (core/lsdem.h); only state travels between ranks.
------------------------------------------------------------------------- */

#ifdef ATOM_CLASS
// clang-format off
AtomStyle(lsdem,AtomVecLsdem);
// clang-format on
#else

#ifndef LMP_ATOM_VEC_LSDEM_H
#define LMP_ATOM_VEC_LSDEM_H

#include "atom_vec.h"
#include "lsdem_kernel.h"
#include "lsdem_lammps_compat.h"

#include <string>

namespace LAMMPS_NS {

class AtomVecLsdem : public AtomVec {
 public:
  // Addresses of the custom per-atom arrays. One instance per Atom object, kept outside
  // the AtomVec (see atom_vec_lsdem.cpp) because AtomVec destructors free the arrays
  // through these addresses after the style object itself is gone (atom_style hybrid).
  struct Storage {
    int *shape;
    double **quat;
    double **inertia;
    double **dwprev;
  };

  AtomVecLsdem(class LAMMPS *);
  ~AtomVecLsdem() override;
  void process_args(int, char **) override;
  void init() override;

  void grow_pointers() override;
  void create_atom_post(int) override;
  void data_atom(double *, imageint, LSDEM_DATA_ATOM_VALUES) override;
#if LSDEM_CHECK_DATA_LINES
  void data_vel(int, char **) override;
#endif
  void data_atom_post(int) override;
  void pack_data_pre(int) override;
  void pack_data_post(int) override;
  void unpack_restart_init(int) override;

  int property_atom(LsdemCompat::PropertyName) override;
  void pack_property_atom(int, double *, int, int) override;

  // the interface the LSDEM styles use (refreshed by grow_pointers)
  int *shape;        // 0-based library index
  double **quat;     // (w,x,y,z): principal frame -> world
  double **inertia;  // principal moments, mass*length^2
  double **dwprev;   // previous corrector increment Delta omega^{n-1}, body frame

  const lsdem_library *library() const { return lib; }
  // lsdem_library_shape inline (every style asks it for every grain every step): the
  // library's shapes are one array, of nshape_open shapes from shape0; nullptr out of range
  const lsdem_shape *shape_of(int i) const
  {
    const int s = shape[i];
    return s >= 0 && s < nshape_open ? shape0 + s : nullptr;
  }
  int nshapes() const { return lsdem_library_count(lib); }
  double max_shape_radius() const { return maxradius; }

  // smallest bounding radius of a shape with nodes (not a sphere), HUGE_VAL when none:
  // the scale of the contact styles' automatic node-list skin (LsdemContactOptions)
  double smallest_grain_radius() const { return min_grain_radius; }
  // An error that per-step code finds on some ranks, reported by all: every rank calls
  // this at the same point with its own message ("" when it found nothing). When any rank
  // has one, all stop through error->all with the message of the lowest such rank (and
  // "(found on rank N)" when N > 0), so that rank 0 writes it to the log and every rank
  // exits normally (an error->one on rank > 0 kills rank 0 with its log unwritten, and with
  // -screen none the message is lost too); every rank flushes its stdio streams first.
  // Costs one MPI_Allreduce of an int when nothing is wrong. file, line: FLERR of the caller.
  static void stop_if_any_rank(class LAMMPS *, const char *file, int line,
                               const std::string &mesg);
  // A problem a style finds on this rank between collective checks (a grain through a
  // wall, fix wall/lsdem), stopped at the next check of fix nve/lsdem (stop_if_any_rank,
  // which takes it): the first one is kept.
  void defer_stop(const std::string &mesg)
  {
    if (deferred_stop.empty()) deferred_stop = mesg;
  }
  std::string take_deferred_stop()
  {
    std::string m;
    m.swap(deferred_stop);
    return m;
  }

 private:
  Storage *store;
  lsdem_library *lib;
  const lsdem_shape *shape0;  // the library's first shape, and their number (shape_of)
  int nshape_open;
  std::string libpath;
  double maxradius;
  double min_grain_radius;  // smallest bounding radius of a non-sphere shape (HUGE_VAL: none)
  double *radius, *rmass;
  double **omega;
  double rmass_one;  // saved by pack_data_pre for pack_data_post
  std::string deferred_stop;

  void register_peratom(const char *, void *, int, int);
  std::string body_mismatch(int) const;
  std::string repeated_ids() const;
  std::string data_file_checked;  // read_data file (and atom count) check_atoms_count read
  void check_atoms_count();
#if LSDEM_CHECK_DATA_LINES
  void check_data_line(char **, int, int, const char *, const char *, const std::string &);
#endif
  void open_library(const char *);
  void report_library();
};

}    // namespace LAMMPS_NS

#endif
#endif
