// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Goodness-of-fit helpers for the random-number and trial-move tests (chi-square with bounds).
#ifndef TAPMC_MC_TEST_STATS_H
#define TAPMC_MC_TEST_STATS_H

#include <cmath>
#include <vector>

namespace tapmc {
namespace test_stats {

// Pearson statistic of observed counts against expected counts.
inline double chi_square(const std::vector<long> &observed, const std::vector<double> &expected)
{
  double chi2 = 0.0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    const double diff = observed[k] - expected[k];
    chi2 += diff * diff / expected[k];
  }
  return chi2;
}

// Quantile of the chi-square law with `dof` degrees of freedom at the standard-normal quantile
// z (Wilson-Hilferty cube-root approximation, accurate to ~1% for dof >= 10). z = +-4.753
// gives the 1e-6 tails: a correct generator fails a test with probability 2e-6.
inline double chi_square_quantile(int dof, double z)
{
  const double v = 2.0 / (9.0 * dof);
  const double c = 1.0 - v + z * std::sqrt(v);
  return dof * c * c * c;
}
constexpr double kZ6 = 4.753;  // standard-normal quantile of 1 - 1e-6

// Expects chi2 inside the two-sided 1e-6 band (too good a fit is as suspect as too bad).
inline bool chi_square_plausible(double chi2, int dof)
{
  return chi2 > chi_square_quantile(dof, -kZ6) && chi2 < chi_square_quantile(dof, kZ6);
}

}  // namespace test_stats
}  // namespace tapmc

#endif
