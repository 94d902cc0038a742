/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute shearband/lsdem: the shear band(s) of the grains flagged by a per-atom indicator,
   planes fitted robustly (core lsdem_shearband_fit), and a per-grain band flag.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(shearband/lsdem,ComputeShearbandLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_SHEARBAND_LSDEM_H
#define LMP_COMPUTE_SHEARBAND_LSDEM_H

#include "compute.h"
#include "lsdem_kernel.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeShearbandLsdem : public Compute {
 public:
  ComputeShearbandLsdem(class LAMMPS *, int, char **);
  ~ComputeShearbandLsdem() override;
  void init() override;
  void compute_vector() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  std::string id_source;        // the per-atom compute read
  int column;                   // its column (1-based), 0 for a per-atom vector
  class Compute *source;
  lsdem_shearband_params params;
  std::string theory_var[2];    // phi, psi: equal-style variables (degrees), or empty
  int ivar[2];
  double kernel;                // FWHM of the indicator's own smoothing (length), 0: none
  double bin;                   // profile bins (length); 0: half the D50
  int nmax;
  double *flag;                 // per atom: 0, or the band (1, 2) the grain is in
  std::vector<double> rows;     // every group grain: tag, x, y, z, value, volume

  void measure();
  class AtomVecLsdem *avec;
  int gather_rows(std::vector<int> &count);
  void measure_widths(int n, const double *x, const double *value, const double *volume,
                      const lsdem_shearband_plane *plane, int nplanes, double *out);
  void store_flags(const std::vector<int> &band, const std::vector<int> &order,
                   const std::vector<int> &count);
};

}    // namespace LAMMPS_NS

#endif
#endif
