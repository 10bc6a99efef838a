// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the biased trial displacement (paper eq. 1): bounds and exact distributions.
#include "mc_test_stats.h"
#include "tapmc_trial_move.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_stats;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(TrialMove, StepIsBoundedAndNeverUp)
{
  const TrialMoveSampler sampler(0.2, kPi / 4);
  const CounterRandom rng(1, 2);
  for (std::uint64_t t = 0; t < 200000; ++t) {
    const TrialDraw d = sampler.draw(rng, t, 0);
    const double len = std::sqrt(d.move.dx * d.move.dx + d.move.dy * d.move.dy + d.move.dz * d.move.dz);
    ASSERT_LE(len, 0.2 * (1 + 1e-15));
    ASSERT_LE(d.move.dz, 0.0);
  }
}

// The Cartesian step is the polar draw: d sin(theta) cos(phi), d sin(theta) sin(phi),
// -d cos(theta), with the same random numbers.
TEST(TrialMove, CartesianStepMatchesPolarDraw)
{
  const TrialMoveSampler sampler(0.37, 0.5);
  const CounterRandom rng(8, 9);
  for (std::uint64_t t = 0; t < 1000; ++t) {
    const TrialDraw d = sampler.draw(rng, t, 0);
    const TrialMoveSampler::Polar p = sampler.draw_polar(rng, t);
    EXPECT_NEAR(d.move.dx, p.d * std::sin(p.theta) * std::cos(p.phi), 1e-15);
    EXPECT_NEAR(d.move.dy, p.d * std::sin(p.theta) * std::sin(p.phi), 1e-15);
    EXPECT_NEAR(d.move.dz, -p.d * std::cos(p.theta), 1e-15);
  }
}

// theta histogram against the truncated Gaussian of eq. 1 (expected counts from its exact
// CDF), several widths and seeds; theta never outside [0, pi/2].
TEST(TrialMove, ThetaFollowsTruncatedGaussian)
{
  for (double theta0 : {kPi / 4, 0.2, kPi / 2}) {
    const TrialMoveSampler sampler(1.0, theta0);
    const ThetaSampler &ts = sampler.theta_sampler();
    for (std::uint64_t seed : {1ull, 2ull}) {
      const CounterRandom rng(seed, 17);
      const int bins = 60, n = 600000;
      std::vector<long> counts(bins, 0);
      for (int t = 0; t < n; ++t) {
        const double th = sampler.draw_polar(rng, t).theta;
        ASSERT_GE(th, 0.0);
        ASSERT_LE(th, kPi / 2);
        ++counts[std::min(bins - 1, static_cast<int>(th / (kPi / 2) * bins))];
      }
      // Merge sparse tail bins (expected < 20) into their neighbour for a valid chi-square.
      std::vector<long> obs;
      std::vector<double> expct;
      double acc_e = 0;
      long acc_o = 0;
      for (int k = 0; k < bins; ++k) {
        acc_e += n * (ts.cdf((k + 1) * kPi / 2 / bins) - ts.cdf(k * kPi / 2 / bins));
        acc_o += counts[k];
        if (acc_e >= 20 || k == bins - 1) {
          obs.push_back(acc_o);
          expct.push_back(acc_e);
          acc_e = 0;
          acc_o = 0;
        }
      }
      const double chi2 = chi_square(obs, expct);
      const int dof = static_cast<int>(obs.size()) - 1;
      EXPECT_TRUE(chi_square_plausible(chi2, dof))
          << "theta0 " << theta0 << " seed " << seed << " chi2 " << chi2 << " dof " << dof;
    }
  }
}

// The density of the sampler is eq. 1 normalised on [0, pi/2], and the CDF its integral.
TEST(TrialMove, ThetaDensityIsNormalisedEquationOne)
{
  const ThetaSampler ts(kPi / 4);
  const int steps = 200000;
  double integral = 0;
  for (int k = 0; k < steps; ++k) {
    const double a = k * (kPi / 2) / steps, b = (k + 1) * (kPi / 2) / steps;
    integral += 0.5 * (ts.density(a) + ts.density(b)) * (b - a);
    if (k % 20000 == 0) EXPECT_NEAR(ts.cdf(b), integral, 1e-9);
  }
  EXPECT_NEAR(integral, 1.0, 1e-9);
  // Shape: P(theta) / P(0) = exp(-(theta / theta0)^2).
  EXPECT_NEAR(ts.density(kPi / 4) / ts.density(0), std::exp(-1.0), 1e-15);
  EXPECT_NEAR(ts.density(kPi / 2) / ts.density(0), std::exp(-4.0), 1e-15);
}

TEST(TrialMove, PhiAndLengthAreUniform)
{
  const TrialMoveSampler sampler(0.3, kPi / 4);
  const CounterRandom rng(5, 6);
  const int bins = 50, n = 500000;
  std::vector<long> phi_counts(bins, 0), d_counts(bins, 0);
  for (int t = 0; t < n; ++t) {
    const TrialMoveSampler::Polar p = sampler.draw_polar(rng, t);
    ASSERT_GE(p.phi, 0.0);
    ASSERT_LT(p.phi, 2 * kPi);
    ASSERT_GE(p.d, 0.0);
    ASSERT_LE(p.d, 0.3);
    ++phi_counts[std::min(bins - 1, static_cast<int>(p.phi / (2 * kPi) * bins))];
    ++d_counts[std::min(bins - 1, static_cast<int>(p.d / 0.3 * bins))];
  }
  const std::vector<double> flat(bins, double(n) / bins);
  EXPECT_TRUE(chi_square_plausible(chi_square(phi_counts, flat), bins - 1));
  EXPECT_TRUE(chi_square_plausible(chi_square(d_counts, flat), bins - 1));
}

TEST(TrialMove, PickIsUniformOverMovableSpheres)
{
  const TrialMoveSampler sampler(0.2, kPi / 4);
  const CounterRandom rng(11, 12);
  const std::uint32_t n_pick = 37;
  const int n = 370000;
  std::vector<long> counts(n_pick, 0);
  for (int t = 0; t < n; ++t) {
    const TrialDraw d = sampler.draw(rng, t, n_pick);
    ASSERT_LT(d.pick, n_pick);
    ++counts[d.pick];
  }
  EXPECT_TRUE(chi_square_plausible(chi_square(counts, std::vector<double>(n_pick, double(n) / n_pick)),
                                   n_pick - 1));
}

// The pick and the displacement are independent: the mean dz of trials that pick an even
// index equals that of odd ones (within 5 sigma).
TEST(TrialMove, PickIndependentOfDisplacement)
{
  const TrialMoveSampler sampler(1.0, kPi / 4);
  const CounterRandom rng(21, 22);
  double sum[2] = {0, 0}, sum2[2] = {0, 0};
  long cnt[2] = {0, 0};
  for (int t = 0; t < 400000; ++t) {
    const TrialDraw d = sampler.draw(rng, t, 2);
    sum[d.pick] += d.move.dz;
    sum2[d.pick] += d.move.dz * d.move.dz;
    ++cnt[d.pick];
  }
  const double m0 = sum[0] / cnt[0], m1 = sum[1] / cnt[1];
  const double v = sum2[0] / cnt[0] - m0 * m0;
  EXPECT_LT(std::fabs(m0 - m1), 5 * std::sqrt(v / cnt[0] + v / cnt[1]));
}

TEST(TrialMove, BadParametersThrowNamingTheParameter)
{
  auto message = [](double d_max, double theta0) {
    try {
      TrialMoveSampler s(d_max, theta0);
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(0.0, 0.5).find("d_max"), std::string::npos);
  EXPECT_NE(message(-1.0, 0.5).find("d_max"), std::string::npos);
  EXPECT_NE(message(INFINITY, 0.5).find("d_max"), std::string::npos);
  EXPECT_NE(message(0.1, 0.0).find("theta0"), std::string::npos);
  EXPECT_NE(message(0.1, 1.6).find("theta0"), std::string::npos);
  EXPECT_NE(message(0.1, NAN).find("theta0"), std::string::npos);
  EXPECT_EQ(message(0.1, kPi / 2), "");
}

// The batched draw (lane-parallel random blocks) is bit-identical to the one-by-one draw.
TEST(TrialMove, BatchDrawEqualsSingleDraws)
{
  const TrialMoveSampler sampler(0.2, 0.3);
  const CounterRandom rng(31, 32);
  std::vector<TrialDraw> batch(TrialMoveSampler::kBatchMax);
  for (std::uint64_t first : {0ull, 5ull, 1ull << 33}) {
    sampler.draw_batch(rng, first, TrialMoveSampler::kBatchMax, 1000, batch.data());
    for (int k = 0; k < TrialMoveSampler::kBatchMax; ++k) {
      const TrialDraw one = sampler.draw(rng, first + k, 1000);
      EXPECT_EQ(one.pick, batch[k].pick);
      EXPECT_EQ(one.move.dx, batch[k].move.dx);
      EXPECT_EQ(one.move.dy, batch[k].move.dy);
      EXPECT_EQ(one.move.dz, batch[k].move.dz);
    }
  }
}

// The table sin/cos agree with the library functions to a few ulp over the whole range.
TEST(TrialMove, SinCosTableIsAccurate)
{
  const SinCosTable table(kPi / 2);
  double worst = 0;
  for (int k = 0; k <= 100000; ++k) {
    const double a = k * (kPi / 2) / 100000;
    double s, c;
    table.sincos(a, s, c);
    worst = std::max({worst, std::fabs(s - std::sin(a)), std::fabs(c - std::cos(a))});
  }
  EXPECT_LT(worst, 1e-15);
}
