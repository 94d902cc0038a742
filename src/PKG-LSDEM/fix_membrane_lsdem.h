/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix membrane/lsdem: confining pressure on the triaxial test's flexible membrane
   (report §2.3.5: p times a third of each triangle's area on its vertices, along the
   inward normal), the enclosed volume (eq 2.30) and the radial stress of the grains on
   the membrane. Triangles come from lsdem-shape membrane; the membrane is ordinary,
   domain-decomposed atoms.
   The triangle loops run in two phases: each triangle's vertices and terms into a buffer
   (the part fix membrane/lsdem/omp shares among threads), then the sums and the scatter
   onto the vertices in triangle order (serial: the same bits on any thread count).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(membrane/lsdem,FixMembraneLsdem);
// clang-format on
#else

#ifndef LMP_FIX_MEMBRANE_LSDEM_H
#define LMP_FIX_MEMBRANE_LSDEM_H

#include "fix.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

class FixMembraneLsdem : public Fix {
 protected:
  typedef void (FixMembraneLsdem::*TrianglePhase)(int from, int to);
  // phase(0, ntri) (fix membrane/lsdem/omp: each thread a contiguous run of the triangles)
  virtual void for_triangles(TrianglePhase phase) { (this->*phase)(0, ntriangles()); }
  int ntriangles() const { return (int) tri_layer.size(); }

 public:
  FixMembraneLsdem(class LAMMPS *, int, char **);
  ~FixMembraneLsdem() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;
  // the triangles (3 vertex tags each) and their layers (0 inner), for fix field/lsdem
  const std::vector<tagint> &triangle_tags() const { return tri; }
  const std::vector<int> &triangle_layers() const { return tri_layer; }

 private:
  // the triangles file
  std::string file;
  double axis[2], specimen_radius, sphere_radius[2];
  int nlayers;
  bigint ninner;  // inner-layer spheres
  std::vector<tagint> vtag, tri, cap;
  std::vector<int> tri_layer, cap_layer, cap_end;
  std::unordered_map<tagint, int> role_of;  // tag -> ROLE_* bits

  // pressure
  double pressure_value, weight[2], knb, tributary_area, checked_pressure;
  double layer_scale[2];  // pressure factor per layer: 1 and A_inner / A_outer (as generated)
  double area0[2];        // lateral areas of the layers as generated (file)
  bool on_specimen;       // surface specimen: P acts on the specimen's surface area
  double specimen_share;  // Rs / (Rs + r_b): specimen area per inner centre-surface area
  std::string pstr;
  int pvar;

  // per local+ghost atom
  int nmax;
  double **fpress;  // pressure force (3) and inner-layer tributary area (1), reverse-summed
  int *role;        // ROLE_* bits of the atom (0: not a membrane sphere)

  // per triangle, phase one of the loops: local indices of the vertices (tvert[3t] < 0:
  // not this rank's triangle, or TRI_MISSING) and terms (pressure: force per vertex (3),
  // specimen-area share (1); geometry: volume term, area)
  std::vector<int> tvert;
  std::vector<double> tterm;

  // radial stress, partial sums of the last post_force (this rank)
  double contact_radial, middle_area;
  // cached output
  double vec[6];
  bigint vec_step, radial_step;

  class BondLsdemMembrane *bond;

  std::string read_file();  // "" or what is wrong
  std::string missing;       // this rank's first missing-vertex error, "" when none
  void bcast_file();
  void current_pressure();
  void check_apparatus(double p);
  void grow();
  void refresh_roles();
  int vertex(tagint tag, int owner) const;
  int triangle_vertices(int t, int v[3]) const;
  bool owned_vertices(int t, int *v) const;
  void note_missing_vertex(int t);
  double radial_projection(int i, const double *f) const;
  double specimen_area_share(const double *a, const double *b, const double *c,
                             const double *S) const;
  void pressure_terms(int from, int to);
  void geometry_terms(int from, int to);
  void apply_pressure();
  double contact_radial_sum() const;
  void reduce_radial_stress();
  void compute_geometry();
};

}    // namespace LAMMPS_NS

#endif
#endif
