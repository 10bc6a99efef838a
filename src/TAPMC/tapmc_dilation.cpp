// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
#include "tapmc_dilation.h"

#include <algorithm>
#include <limits>

namespace tapmc {

double dilate_about_floor(double *xyz, const int *mask, int groupbit, int n, double z_floor,
                          double eps)
{
  const double factor = 1.0 + eps;
  double zmax = -std::numeric_limits<double>::infinity();
  if (!mask) {
    for (int i = 0; i < n; ++i) {
      double &z = xyz[3 * i + 2];
      z = z_floor + (z - z_floor) * factor;
      zmax = std::max(zmax, z);
    }
    return zmax;
  }
  for (int i = 0; i < n; ++i) {
    if (!(mask[i] & groupbit)) continue;
    double &z = xyz[3 * i + 2];
    z = z_floor + (z - z_floor) * factor;
    zmax = std::max(zmax, z);
  }
  return zmax;
}

}  // namespace tapmc
