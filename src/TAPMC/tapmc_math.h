// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Mathematical constants, the periodic wrap and number formatting shared by the kernels (and the
// pore tool), written once.
#ifndef TAPMC_MATH_H
#define TAPMC_MATH_H

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace tapmc {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;  // exact: doubling a double does not round
constexpr double kSqrtPi = 1.77245385090551602730;

// Wraps x into [lo, hi) along a periodic axis of length `length` (= hi - lo), counting the
// periods removed in `periods` (x_unwrapped = x_wrapped + periods * length). A coordinate
// already inside comes back unchanged (not recomputed); any distance works; a result that
// rounding at the seam would put at hi lands on lo (the same point modulo the length).
inline double wrap_periodic_periods(double x, double lo, double hi, double length,
                                    double &periods)
{
  periods = 0.0;
  if (x >= lo && x < hi) return x;
  double k = std::floor((x - lo) / length);
  x -= k * length;
  if (x < lo) {
    x += length;
    k -= 1.0;
  } else if (x >= hi) {
    x -= length;
    k += 1.0;
  }
  if (!(x >= lo && x < hi)) x = lo;
  periods = k;
  return x;
}

// The same, adding the periods to an integer image count (the LAMMPS image-flag convention).
inline double wrap_periodic(double x, double lo, double hi, double length, int &image)
{
  double periods;
  x = wrap_periodic_periods(x, lo, hi, length, periods);
  image += static_cast<int>(periods);
  return x;
}

// The same when the number of periods is not needed.
inline double wrap_periodic(double x, double lo, double hi)
{
  double periods;
  return wrap_periodic_periods(x, lo, hi, hi - lo, periods);
}

// A value as error messages quote it: the shortest decimal that reads back as the same double
// (at most 17 significant digits), so messages quote "-0.1", as typed, and
// still distinguish values that differ in the last bit. A whole number is written without an
// exponent where that is shorter ("10", "1500", but "1e+06").
inline std::string number(double value)
{
  char buffer[64];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  if (std::strchr(buffer, 'e') && std::fabs(value) < 1e17 && value == std::floor(value)) {
    char whole[64];
    std::snprintf(whole, sizeof whole, "%.0f", value);
    if (std::strlen(whole) <= std::strlen(buffer)) return whole;
  }
  return buffer;
}

}  // namespace tapmc

#endif
