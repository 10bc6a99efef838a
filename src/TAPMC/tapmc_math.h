// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Mathematical constants and number formatting shared by the kernels, written once.
#ifndef TAPMC_MATH_H
#define TAPMC_MATH_H

#include <cstdio>
#include <cstdlib>
#include <string>

namespace tapmc {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;  // exact: doubling a double does not round
constexpr double kSqrtPi = 1.77245385090551602730;

// A value as error messages quote it: 17 significant digits, so it reads back to the same double.
// The shortest decimal that reads back as the same double: messages quote "-0.1", as typed, and
// still distinguish values that differ in the last bit.
inline std::string number(double value)
{
  char buffer[64];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace tapmc

#endif
