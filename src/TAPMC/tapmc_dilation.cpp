// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
#include "tapmc_dilation.h"

#include "tapmc_checks.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {

void validate(const DilationParams &params)
{
  if (!(params.eps >= 0.0 && params.eps <= defaults::kMaxTapEps))
    throw_outside_range("eps", params.eps,
                        "[0, " + number(defaults::kMaxTapEps) +
                            "] (relative dilation of the heights above the floor; eps = " +
                            number(defaults::kMaxTapEps) + " doubles them)");
  if (params.every < 1) throw_outside_range("every", params.every, "[1, +inf)");
  if (!std::isfinite(params.z_floor)) throw_outside_range("floor", params.z_floor, "(finite)");
}

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
