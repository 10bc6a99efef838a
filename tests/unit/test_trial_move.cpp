// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the biased trial displacement (paper eq. 1): bounds and exact distributions.
#include "mc_test_stats.h"
#include "tapmc_defaults.h"
#include "tapmc_trial_move.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_stats;


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
  EXPECT_NE(message(0.1, 1001.0).find("theta0"), std::string::npos);  // 1.6 is allowed since
                                                                      // theta0 may exceed pi/2
  EXPECT_NE(message(0.1, NAN).find("theta0"), std::string::npos);
  EXPECT_EQ(message(0.1, kPi / 2), "");
}

// The batched draw (lane-parallel random blocks, a lane-parallel pass over the draws that need
// no rejection step, finish() for the others) is bit-identical to the one-by-one draw: theta0
// with and without tail strips, picks with frequent rejections (n = 3 2^30: a quarter of the
// first words is rejected), no pick, and batch sizes that leave partial vectors.
TEST(TrialMove, BatchDrawEqualsSingleDraws)
{
  for (double theta0 : {defaults::kThetaWidth, 0.3, 0.05, kPi / 2}) {
    const TrialMoveSampler sampler(0.2, theta0);
    if (theta0 == 0.05) EXPECT_GT(sampler.theta_sampler().tail_strips(), 0);
    const CounterRandom rng(31, 32);
    std::vector<TrialDraw> batch(TrialMoveSampler::kBatchMax);
    for (std::uint32_t n_pick : {1000u, 3u << 30, 0u}) {
      for (int count : {TrialMoveSampler::kBatchMax, 37, 1}) {
        for (std::uint64_t first : {0ull, 5ull, 1ull << 33}) {
          for (int repeat = 0; repeat < 40; ++repeat) {
            const std::uint64_t start = first + static_cast<std::uint64_t>(repeat) * 1000;
            sampler.draw_batch(rng, start, count, n_pick, batch.data());
            for (int k = 0; k < count; ++k) {
              const TrialDraw one = sampler.draw(rng, start + k, n_pick);
              ASSERT_EQ(one.pick, batch[k].pick) << theta0 << " " << n_pick << " " << start + k;
              ASSERT_EQ(one.move.dx, batch[k].move.dx) << theta0 << " " << start + k;
              ASSERT_EQ(one.move.dy, batch[k].move.dy) << theta0 << " " << start + k;
              ASSERT_EQ(one.move.dz, batch[k].move.dz) << theta0 << " " << start + k;
            }
          }
        }
      }
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

namespace {

// Kolmogorov-Smirnov statistic sqrt(n) D of sorted samples against a CDF.
template <class Cdf> double ks_statistic(std::vector<double> samples, Cdf &&cdf)
{
  std::sort(samples.begin(), samples.end());
  const double n = static_cast<double>(samples.size());
  double d = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double f = cdf(samples[k]);
    d = std::max({d, f - k / n, (k + 1) / n - f});
  }
  return std::sqrt(n) * d;
}
// P(sqrt(n) D > k) ~ 2 exp(-2 k^2): 2.69 is the 1e-6 tail of the Kolmogorov law.
constexpr double kKolmogorov6 = 2.69;

}  // namespace

// Eq. 1 exactly for every theta0 of the allowed range, from very narrow (0.01: almost every
// move vertical) to the flat-topped pi/2: the whole law (KS and equal-probability chi-square
// against the exact CDF) and, separately, the last strip [~2 theta0, pi/2], whose flat envelope
// was the inefficient one at small theta0 (conditional KS with erfc, exact in the far tail).
TEST(TrialMove, ThetaIsExactForEveryWidth)
{
  for (double theta0 : {0.01, 0.03, 0.1, 0.15, 0.2, 0.5, kPi / 4, 1.2, kPi / 2}) {
    const TrialMoveSampler sampler(1.0, theta0);
    const ThetaSampler &ts = sampler.theta_sampler();
    const CounterRandom rng(99, 5);
    const int n = 300000, bins = 100;
    std::vector<double> theta(n);
    std::vector<long> counts(bins, 0);
    for (int t = 0; t < n; ++t) {
      theta[t] = sampler.draw_polar(rng, t).theta;
      ASSERT_GE(theta[t], 0.0);
      ASSERT_LE(theta[t], kPi / 2);
      ++counts[std::min(bins - 1, static_cast<int>(ts.cdf(theta[t]) * bins))];
    }
    EXPECT_LT(ks_statistic(theta, [&](double x) { return ts.cdf(x); }), kKolmogorov6)
        << "theta0 " << theta0;
    EXPECT_TRUE(chi_square_plausible(chi_square(counts, std::vector<double>(bins, double(n) / bins)),
                                     bins - 1))
        << "theta0 " << theta0;
  }
  for (double theta0 : {1e-200, 1e-6, 0.01, 0.1, 0.2, kPi / 4, kPi / 2}) {
    const ThetaSampler ts(theta0);
    const CounterRandom rng(3, 4);
    // left edge of the last strip: cdf(left) = 255/256
    double lo = 0.0, hi = kPi / 2;
    for (int it = 0; it < 2000 && hi - lo > 0.0; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (ts.cdf(mid) < 255.0 / 256 ? lo : hi) = mid;
    }
    const double left = 0.5 * (lo + hi);
    const double tail_left = std::erfc(left / theta0), tail_top = std::erfc(kPi / 2 / theta0);
    const int n = 100000;
    std::vector<double> theta(n);
    std::uint64_t position = 0;
    for (int k = 0; k < n; ++k)
      theta[k] = ts.sample(0xFF000000u, [&](std::uint32_t &p, std::uint32_t &u) {
        const RandomBlock b = rng.block(position++);
        p = b[0];
        u = b[1];
      });
    for (double x : theta) {
      ASSERT_GE(x, left * (1 - 1e-12));
      ASSERT_LE(x, kPi / 2);
    }
    EXPECT_LT(ks_statistic(theta, [&](double x) {
                return (tail_left - std::erfc(x / theta0)) / (tail_left - tail_top);
              }),
              kKolmogorov6)
        << "last strip, theta0 " << theta0;
  }
}

// Every strip accepts more than 0.7 of its proposals whatever theta0 above the subnormal range
// (so a theta needs fewer than ~3 random words on average), and the default pi/4 keeps only
// flat strips (draws of the paper's set-up do not depend on the tail envelope).
TEST(TrialMove, ThetaSamplerIsEfficientForEveryWidth)
{
  for (double theta0 = kPi / 2; theta0 > 1e-300; theta0 *= 0.13) {
    const ThetaSampler ts(theta0);
    EXPECT_GT(ts.min_acceptance(), 0.7) << "theta0 " << theta0;
  }
  // the smallest subnormal: strip edges can only be multiples of theta0 itself
  EXPECT_GT(ThetaSampler(5e-324).min_acceptance(), 0.4);
  EXPECT_EQ(ThetaSampler(kPi / 4).tail_strips(), 0);
  EXPECT_GT(ThetaSampler(0.1).tail_strips(), 0);
}

// The rejection steps never run out of random words: past the trial's slice they continue in
// the overflow rounds (other keys), whose words are fresh (no pair repeats across attempts and
// trials) and uniform.
TEST(TrialMove, RejectionWordsNeverRunOut)
{
  const CounterRandom rng(1234, 56);
  EXPECT_EQ(rng.round(0).block(7), rng.block(7));
  std::uint32_t p, u;
  TrialMoveSampler::theta_words(rng, 3, 2, p, u);
  EXPECT_EQ(p, rng.block(3 * 256 + 2)[0]);
  TrialMoveSampler::theta_words(rng, 3, 253, p, u);
  EXPECT_EQ(u, rng.block(3 * 256 + 127)[3]);
  TrialMoveSampler::theta_words(rng, 3, 254, p, u);  // first pair of overflow round 1
  EXPECT_EQ(p, rng.round(1).block(3 * 256 + 1)[0]);
  EXPECT_EQ(TrialMoveSampler::pick_word(rng, 3, 512), rng.round(1).block(3 * 256 + 128)[0]);

  std::vector<std::uint64_t> pairs;
  std::vector<long> counts(64, 0);
  for (std::uint64_t trial : {0ull, 1ull, 2ull})
    for (std::uint64_t attempt = 0; attempt < 3000; ++attempt) {
      TrialMoveSampler::theta_words(rng, trial, attempt, p, u);
      pairs.push_back(join_u32(p, u));
      if (attempt >= 254) {
        ++counts[p >> 26];
        ++counts[u >> 26];
      }
    }
  std::sort(pairs.begin(), pairs.end());
  EXPECT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end());
  const double expected = 2.0 * 3 * (3000 - 254) / 64;
  EXPECT_TRUE(chi_square_plausible(chi_square(counts, std::vector<double>(64, expected)), 63));

  // A strip sampler fed only rejected proposals for 1000 attempts still ends with a valid theta.
  const ThetaSampler ts(0.1);
  int calls = 0;
  const double theta = ts.sample(0xFF000000u, [&](std::uint32_t &pos, std::uint32_t &acc) {
    pos = 0x80000000u;
    acc = ++calls <= 1000 ? 0xFFFFFFFFu : 0u;
  });
  EXPECT_EQ(calls, 1001);
  EXPECT_GT(theta, 0.0);
  EXPECT_LE(theta, kPi / 2);
}

// A draw reads its theta words exactly where theta_words says, through every rejection: the
// narrow theta0 = 0.1 rejects often in its tail strips, so many trials reach the third and later
// attempts (words of later blocks, each block serving two attempts).
TEST(TrialMove, DrawUsesTheDocumentedThetaWords)
{
  const CounterRandom rng(99, 7);
  const TrialMoveSampler sampler(0.2, 0.1);
  const ThetaSampler theta(0.1);
  long later_attempts = 0;
  for (std::uint64_t t = 0; t < 20000; ++t) {
    const std::uint32_t strip_word = rng.block(t * TrialMoveSampler::kDrawsPerTrial)[3];
    std::uint64_t attempt = 0;
    const double expected = theta.sample(strip_word, [&](std::uint32_t &p, std::uint32_t &u) {
      TrialMoveSampler::theta_words(rng, t, attempt++, p, u);
    });
    later_attempts += attempt > 2;
    ASSERT_EQ(sampler.draw_polar(rng, t).theta, expected) << "trial " << t;
  }
  EXPECT_GT(later_attempts, 0);
}
