// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the laws of theta (ThetaLaw: eq. 1 per unit angle and per unit solid angle, section
// II's exponential and linear alternatives) and of theta0 beyond pi/2: exact distributions
// against independent quadrature, the flat and narrow limits, efficiency, determinism.
#include "mc_test_stats.h"
#include "tapmc_defaults.h"
#include "tapmc_trial_move.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_stats;

namespace {

constexpr double kHalfPi = 0.5 * kPi;
// P(sqrt(n) D > k) ~ 2 exp(-2 k^2): 2.69 is the 1e-6 tail of the Kolmogorov law.
constexpr double kKolmogorov6 = 2.69;

// The unnormalised density of each law, written out here (not taken from the sampler).
double law_density(ThetaLaw law, double theta0, double theta)
{
  const double x = theta / theta0;
  switch (law) {
    case ThetaLaw::Exponential:
      return std::exp(-x);
    case ThetaLaw::Linear:
      return std::max(0.0, 1.0 - x);
    case ThetaLaw::Solid:
      return std::exp(-x * x) * std::sin(theta);
    case ThetaLaw::Angle:
      break;
  }
  return std::exp(-x * x);
}

constexpr ThetaLaw kAllLaws[] = {ThetaLaw::Angle, ThetaLaw::Solid, ThetaLaw::Exponential,
                                 ThetaLaw::Linear};

// The CDF on [0, pi/2] by composite Simpson quadrature on a fine grid (2^16 intervals: error
// below 1e-12 for theta0 >= pi/16), linear between grid nodes (error h^2 max|p'| / 8, below
// 1e-8 at theta0 = pi/16; the tests resolve 1e-3).
class QuadratureCdf {
 public:
  QuadratureCdf(ThetaLaw law, double theta0) : cum_(kIntervals + 1, 0.0)
  {
    const double h = kHalfPi / kIntervals;
    for (int k = 0; k < kIntervals; ++k) {
      const double a = k * h;
      cum_[k + 1] = cum_[k] + h / 6.0 *
                                  (law_density(law, theta0, a) +
                                   4.0 * law_density(law, theta0, a + 0.5 * h) +
                                   law_density(law, theta0, a + h));
    }
    for (double &c : cum_) c /= cum_.back();
  }
  double operator()(double theta) const
  {
    if (theta <= 0.0) return 0.0;
    if (theta >= kHalfPi) return 1.0;
    const double t = theta / kHalfPi * kIntervals;
    const int k = std::min(kIntervals - 1, static_cast<int>(t));
    return cum_[k] + (t - k) * (cum_[k + 1] - cum_[k]);
  }

 private:
  static constexpr int kIntervals = 1 << 16;
  std::vector<double> cum_;
};

double ks_statistic(std::vector<double> x, const std::function<double(double)> &cdf)
{
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, f - i / n, (i + 1) / n - f});
  }
  return std::sqrt(n) * d;
}

// theta of n draws of the full trial move (the random keying of the runs).
std::vector<double> sample_theta(const TrialMoveSampler &sampler, std::uint64_t seed, int n)
{
  const CounterRandom rng(seed, 11);
  std::vector<double> theta(n);
  for (int t = 0; t < n; ++t) theta[t] = sampler.draw_polar(rng, t).theta;
  return theta;
}

const char *name(ThetaLaw law)
{
  const char *names[] = {"angle", "solid", "exponential", "linear"};
  return names[static_cast<int>(law)];
}

}  // namespace

// Each law at theta0 = pi/16, pi/4, pi/2, 3 and 100: the sampled theta against the CDF of its
// density by independent quadrature (Kolmogorov, and chi-square on 64 equal-width bins with
// sparse bins merged), and the sampler's own density and CDF against the same quadrature.
TEST(ThetaLaw, SamplesFollowTheExactCdfOfEachLaw)
{
  for (ThetaLaw law : kAllLaws)
    for (double theta0 : {kPi / 16, kPi / 4, kPi / 2, 3.0, 100.0}) {
      const TrialMoveSampler sampler(1.0, theta0, law);
      const ThetaSampler &ts = sampler.theta_sampler();
      const QuadratureCdf cdf(law, theta0);
      for (double th = 0.0; th <= kHalfPi; th += kHalfPi / 97)
        ASSERT_NEAR(ts.cdf(th), cdf(th), 1e-8) << name(law) << " theta0 " << theta0;
      const int n = 200000, bins = 64;
      const std::vector<double> theta = sample_theta(sampler, 7, n);
      std::vector<long> counts(bins, 0);
      for (double th : theta) {
        ASSERT_GE(th, 0.0);
        ASSERT_LE(th, kHalfPi);
        ++counts[std::min(bins - 1, static_cast<int>(th / kHalfPi * bins))];
      }
      EXPECT_LT(ks_statistic(theta, cdf), kKolmogorov6) << name(law) << " theta0 " << theta0;
      std::vector<long> obs;
      std::vector<double> expected;
      long acc_o = 0;
      double acc_e = 0.0;
      for (int k = 0; k < bins; ++k) {
        acc_o += counts[k];
        acc_e += n * (cdf((k + 1) * kHalfPi / bins) - cdf(k * kHalfPi / bins));
        if (acc_e >= 20) {
          obs.push_back(acc_o);
          expected.push_back(acc_e);
          acc_o = 0;
          acc_e = 0.0;
        }
      }
      // what is left (sparse bins at the top; none past the end of the linear law) joins the
      // last group
      obs.back() += acc_o;
      expected.back() += acc_e;
      const int dof = static_cast<int>(obs.size()) - 1;
      EXPECT_TRUE(chi_square_plausible(chi_square(obs, expected), dof))
          << name(law) << " theta0 " << theta0 << " chi2 " << chi_square(obs, expected)
          << " dof " << dof;
    }
}

// The solid law's density is normalised and has the shape exp(-(theta/theta0)^2) sin(theta).
TEST(ThetaLaw, SolidDensityIsNormalisedEquationOneTimesSin)
{
  for (double theta0 : {0.05, kPi / 4, 3.0}) {
    const ThetaSampler ts(theta0, ThetaLaw::Solid);
    const int steps = 100000;
    double integral = 0.0;
    for (int k = 0; k < steps; ++k) {
      const double a = k * kHalfPi / steps, b = (k + 1) * kHalfPi / steps;
      integral += (b - a) / 6 * (ts.density(a) + 4 * ts.density(0.5 * (a + b)) + ts.density(b));
    }
    EXPECT_NEAR(integral, 1.0, 1e-10) << theta0;
    EXPECT_EQ(ts.density(0.0), 0.0);
    const double a = 0.3 * theta0, b = 0.9 * std::min(theta0, 1.0);
    EXPECT_NEAR(ts.density(b) / ts.density(a),
                law_density(ThetaLaw::Solid, theta0, b) / law_density(ThetaLaw::Solid, theta0, a),
                1e-13);
  }
}

// Very large theta0: the angle law tends to theta uniform on [0, pi/2], the solid law to
// directions uniform on the downward hemisphere (cos(theta) uniform, CDF 1 - cos(theta)).
TEST(ThetaLaw, LargeWidthGivesTheFlatLimits)
{
  for (double theta0 : {100.0, defaults::kThetaWidthMax}) {
    const ThetaSampler angle(theta0, ThetaLaw::Angle), solid(theta0, ThetaLaw::Solid);
    const double tol = 2.0 * std::pow(kHalfPi / theta0, 2);  // 1 - exp(-(pi/2 / theta0)^2)
    for (double th = 0.0; th <= kHalfPi; th += 0.01) {
      EXPECT_NEAR(angle.cdf(th), th / kHalfPi, tol) << theta0;
      EXPECT_NEAR(solid.cdf(th), 1.0 - std::cos(th), tol) << theta0;
    }
    for (ThetaLaw law : {ThetaLaw::Angle, ThetaLaw::Solid}) {
      const std::vector<double> theta = sample_theta(TrialMoveSampler(0.1, theta0, law), 3, 200000);
      EXPECT_LT(ks_statistic(theta,
                             [law](double th) {
                               return law == ThetaLaw::Solid ? 1.0 - std::cos(th) : th / kHalfPi;
                             }),
                kKolmogorov6)
          << name(law) << " theta0 " << theta0;
    }
  }
}

// Narrow solid law: sin(theta) = theta (1 + O(theta^2)), so theta / theta0 has the density
// 2 x exp(-x^2) and the CDF 1 - exp(-(theta/theta0)^2) (to 1e-4 at theta0 = 0.01). Exercises
// the tail strips and the series of the small-angle tables.
TEST(ThetaLaw, NarrowSolidLawIsTheRayleighLimit)
{
  for (double theta0 : {1e-6, 0.01}) {
    const TrialMoveSampler sampler(0.1, theta0, ThetaLaw::Solid);
    EXPECT_GT(sampler.theta_sampler().tail_strips(), 0) << theta0;
    const std::vector<double> theta = sample_theta(sampler, 9, 200000);
    EXPECT_LT(ks_statistic(theta,
                           [theta0](double th) { return -std::expm1(-std::pow(th / theta0, 2)); }),
              kKolmogorov6)
        << theta0;
  }
}

// Efficiency over the whole range: every strip accepts at least 0.7 (angle) or 0.45 (solid: the
// first strip, where the density rises from 0, accepts ~1/2) of its proposals, and the mean
// number of attempts per theta stays close to 1 (measured: random words drawn per sample).
TEST(ThetaLaw, SamplersStayEfficientUpToTheLargestWidth)
{
  for (double theta0 = defaults::kThetaWidthMax; theta0 > 1e-6; theta0 *= 0.31) {
    EXPECT_GT(ThetaSampler(theta0, ThetaLaw::Angle).min_acceptance(), 0.7) << theta0;
    EXPECT_GT(ThetaSampler(theta0, ThetaLaw::Solid).min_acceptance(), 0.45) << theta0;
  }
  for (double theta0 : {3.0, 100.0, defaults::kThetaWidthMax}) {
    const ThetaSampler ts(theta0, ThetaLaw::Angle);
    EXPECT_GT(ts.min_acceptance(), 0.99) << theta0;  // P is nearly flat on every strip
    EXPECT_EQ(ts.tail_strips(), 0);
  }
  for (ThetaLaw law : {ThetaLaw::Angle, ThetaLaw::Solid})
    for (double theta0 : {kPi / 16, kPi / 4, kPi / 2, 3.0, 100.0}) {
      const ThetaSampler ts(theta0, law);
      const CounterRandom rng(21, 22);
      std::uint64_t position = 0;
      const int n = 100000;
      for (int k = 0; k < n; ++k) {
        const RandomBlock strip = rng.block(position++);
        ts.sample(strip[0], [&](std::uint32_t &p, std::uint32_t &u) {
          const RandomBlock b = rng.block(position++);
          p = b[0];
          u = b[1];
        });
      }
      const double attempts = static_cast<double>(position - n) / n;
      EXPECT_LT(attempts, law == ThetaLaw::Solid ? 1.1 : 1.05)
          << name(law) << " theta0 " << theta0 << ": " << attempts << " attempts per theta";
    }
}

// Same seed, same draws, from samplers built separately; the batched draws (lane-parallel first
// attempt from the solid tables) are bit-identical to single draws.
TEST(ThetaLaw, SolidDrawsAreDeterministicAndBatchesMatchSingleDraws)
{
  for (double theta0 : {0.05, kPi / 4, 30 * kPi}) {
    const TrialMoveSampler a(0.2, theta0, ThetaLaw::Solid), b(0.2, theta0, ThetaLaw::Solid);
    const CounterRandom rng(5, 77);
    std::vector<TrialDraw> batch(TrialMoveSampler::kBatchMax);
    for (std::uint64_t first = 0; first < 20000; first += TrialMoveSampler::kBatchMax) {
      a.draw_batch(rng, first, TrialMoveSampler::kBatchMax, 1000, batch.data());
      for (int k = 0; k < TrialMoveSampler::kBatchMax; ++k) {
        const TrialDraw single = b.draw(rng, first + k, 1000);
        ASSERT_EQ(batch[k].pick, single.pick);
        ASSERT_EQ(batch[k].move.dx, single.move.dx) << theta0;
        ASSERT_EQ(batch[k].move.dy, single.move.dy);
        ASSERT_EQ(batch[k].move.dz, single.move.dz);
        ASSERT_LE(single.move.dz, 0.0);
      }
    }
  }
  // the two laws share the keying but not the draws
  const CounterRandom rng(5, 77);
  const TrialMoveSampler angle(0.2, kPi / 4, ThetaLaw::Angle), solid(0.2, kPi / 4, ThetaLaw::Solid);
  int same = 0;
  for (std::uint64_t t = 0; t < 1000; ++t)
    same += angle.draw(rng, t, 10).move.dz == solid.draw(rng, t, 10).move.dz;
  EXPECT_LT(same, 10);
  // the default law is the angle law
  const TrialMoveSampler plain(0.2, kPi / 4);
  EXPECT_EQ(plain.theta_sampler().law(), ThetaLaw::Angle);
  for (std::uint64_t t = 0; t < 1000; ++t)
    ASSERT_EQ(plain.draw(rng, t, 10).move.dz, angle.draw(rng, t, 10).move.dz);
}

TEST(ThetaLaw, WidthOutsideTheRangeIsRefusedNamingIt)
{
  auto message = [](double theta0, ThetaLaw law) {
    try {
      ThetaSampler ts(theta0, law);
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (ThetaLaw law : kAllLaws) {
    EXPECT_EQ(message(1001.0, law), "theta0 = 1001 is outside the allowed range (0, 1000] (radians)");
    EXPECT_EQ(message(0.0, law), "theta0 = 0 is outside the allowed range (0, 1000] (radians)");
    EXPECT_EQ(message(INFINITY, law), "theta0 = inf is outside the allowed range (0, 1000] (radians)");
    EXPECT_NE(message(NAN, law).find("theta0 = nan"), std::string::npos);
    EXPECT_EQ(message(defaults::kThetaWidthMax, law), "");
    EXPECT_EQ(message(1.6, law), "");
  }
}

// Section II's alternative laws. Exponential: narrow, it is the untruncated exponential (CDF
// 1 - exp(-theta/theta0)); wide, theta uniform. Linear: theta never passes theta0 and comes
// within a hair of it; wide, theta uniform. Each law against the other's CDF: rejected (the
// control: the Kolmogorov test tells these laws apart at this sample size).
TEST(ThetaLaw, AlternativeLawsHaveTheirLimitsAndSupport)
{
  const int n = 200000;
  const std::vector<double> narrow =
      sample_theta(TrialMoveSampler(0.1, 0.01, ThetaLaw::Exponential), 4, n);
  EXPECT_LT(ks_statistic(narrow, [](double th) { return -std::expm1(-th / 0.01); }),
            kKolmogorov6);
  for (ThetaLaw law : {ThetaLaw::Exponential, ThetaLaw::Linear}) {
    const std::vector<double> wide = sample_theta(TrialMoveSampler(0.1, 1e3, law), 5, n);
    // the density departs from flat by at most (pi/2) / theta0 = 1.6e-3
    EXPECT_LT(ks_statistic(wide, [](double th) { return th / kHalfPi; }), kKolmogorov6)
        << name(law);
    const ThetaSampler ts(kPi / 4, law);
    EXPECT_TRUE(ts.by_inversion());
    EXPECT_EQ(ts.min_acceptance(), 1.0);
    EXPECT_EQ(ts.exp_fraction(), 0.0);
    EXPECT_EQ(ts.tail_strips(), 0);
  }
  const double theta0 = kPi / 4;
  const std::vector<double> linear =
      sample_theta(TrialMoveSampler(0.1, theta0, ThetaLaw::Linear), 6, n);
  const double top = *std::max_element(linear.begin(), linear.end());
  EXPECT_LE(top, theta0);
  EXPECT_GT(top, 0.99 * theta0);  // P(all below 0.99 theta0) = (1 - 1e-4)^n ~ 2e-9
  const ThetaSampler linear_law(theta0, ThetaLaw::Linear);
  EXPECT_EQ(linear_law.density(0.5 * (theta0 + kHalfPi)), 0.0);
  EXPECT_EQ(linear_law.cdf(theta0), 1.0);
  const std::vector<double> exponential =
      sample_theta(TrialMoveSampler(0.1, theta0, ThetaLaw::Exponential), 6, n);
  const QuadratureCdf gaussian(ThetaLaw::Angle, theta0), linear_cdf(ThetaLaw::Linear, theta0);
  EXPECT_GT(ks_statistic(exponential, gaussian), 10 * kKolmogorov6);
  EXPECT_GT(ks_statistic(linear, gaussian), 10 * kKolmogorov6);
  EXPECT_GT(ks_statistic(exponential, linear_cdf), 10 * kKolmogorov6);
}

// The inversion laws: draws are deterministic, batches (the lane pass by inversion) are
// bit-identical to single draws, and they share the keying of the other laws but not the draws.
TEST(ThetaLaw, InversionDrawsAreDeterministicAndBatchesMatchSingleDraws)
{
  for (ThetaLaw law : {ThetaLaw::Exponential, ThetaLaw::Linear})
    for (double theta0 : {1e-3, kPi / 4, 30 * kPi}) {
      const TrialMoveSampler a(0.2, theta0, law), b(0.2, theta0, law);
      const CounterRandom rng(5, 78);
      std::vector<TrialDraw> batch(TrialMoveSampler::kBatchMax);
      for (std::uint64_t first = 0; first < 20000; first += TrialMoveSampler::kBatchMax) {
        // n_pick = 3e9: the pick's first word is rejected now and then (finish() redraws)
        a.draw_batch(rng, first, TrialMoveSampler::kBatchMax, 3000000000u, batch.data());
        for (int k = 0; k < TrialMoveSampler::kBatchMax; ++k) {
          const TrialDraw single = b.draw(rng, first + k, 3000000000u);
          ASSERT_EQ(batch[k].pick, single.pick);
          ASSERT_EQ(batch[k].move.dx, single.move.dx) << name(law) << " " << theta0;
          ASSERT_EQ(batch[k].move.dy, single.move.dy);
          ASSERT_EQ(batch[k].move.dz, single.move.dz);
          ASSERT_LE(single.move.dz, 0.0);
        }
      }
    }
  const CounterRandom rng(5, 77);
  const TrialMoveSampler angle(0.2, kPi / 4, ThetaLaw::Angle),
      exponential(0.2, kPi / 4, ThetaLaw::Exponential), linear(0.2, kPi / 4, ThetaLaw::Linear);
  int same = 0;
  for (std::uint64_t t = 0; t < 1000; ++t) {
    const TrialDraw a = angle.draw(rng, t, 10), e = exponential.draw(rng, t, 10),
                    l = linear.draw(rng, t, 10);
    same += (a.move.dz == e.move.dz) + (a.move.dz == l.move.dz) + (e.move.dz == l.move.dz);
    ASSERT_EQ(a.pick, e.pick);  // the pick and the phi of a trial do not depend on the law
    ASSERT_NEAR(a.move.dx * e.move.dy - a.move.dy * e.move.dx, 0.0, 1e-14);  // same phi
  }
  EXPECT_LT(same, 10);
}

// The inversion laws over the whole accepted range, down to the smallest subnormal width: every
// theta finite, within [0, pi/2] and, for the linear law, within its support [0, theta0].
TEST(ThetaLaw, InversionLawsStayInTheirSupportForEveryWidth)
{
  for (ThetaLaw law : {ThetaLaw::Exponential, ThetaLaw::Linear})
    for (double theta0 : {5e-324, 1e-300, 1e-10, 0.5, kHalfPi, 2.0, defaults::kThetaWidthMax}) {
      const TrialMoveSampler sampler(0.2, theta0, law);
      const double top = law == ThetaLaw::Linear ? std::min(theta0, kHalfPi) : kHalfPi;
      const std::vector<double> theta = sample_theta(sampler, 13, 20000);
      for (double th : theta) {
        ASSERT_TRUE(std::isfinite(th)) << name(law) << " theta0 " << theta0;
        ASSERT_GE(th, 0.0);
        ASSERT_LE(th, top) << name(law) << " theta0 " << theta0;
      }
      const ThetaSampler &ts = sampler.theta_sampler();
      EXPECT_EQ(ts.cdf(top), 1.0);
      EXPECT_EQ(ts.cdf(0.0), 0.0);
    }
}
