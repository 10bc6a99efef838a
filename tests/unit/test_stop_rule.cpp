// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the stopping rules of a redeposition (tapmc_stop_rule.h) on synthetic <Z> series
// with an exactly known drift, and of the Drift rule inside the kernel (Settler).
#include "settle_test_scenes.h"
#include "tapmc_settle.h"
#include "tapmc_stop_rule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;

namespace {

// <Z>(s) = Z_inf + A exp(-s / tau) after a tap: the drift per sweep A/tau exp(-s/tau) crosses
// eta <Z> at s* = tau ln(A / (tau eta Z_inf)) (to within 1e-4 relative: <Z> ~ Z_inf there).
// Each sweep's decrement carries Gaussian noise of variance mu b / N (mu the mean decrement):
// the compound-Poisson noise of the accepted moves of N trials, b = 3.9e-4 chosen so that the
// noise is 0.37 of the mean at N = 4096 near s*, as measured on the paper's set-up
// (bench/stop_rule_scaling.py).
struct Relaxation {
  double z_inf = 7.0, amplitude = 0.1, tau = 1000.0, eta = 1e-7, noise_b = 3.9e-4;
  double crossing() const { return tau * std::log(amplitude / (tau * eta * z_inf)); }
};

double gaussian(std::mt19937_64 &bits)
{
  auto uniform = [&] { return (static_cast<double>(bits() >> 11) + 0.5) * 0x1.0p-53; };
  const double u = uniform(), v = uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * 3.141592653589793 * v);
}

// The sweep (one check per sweep) at which `rule` stops on a noisy relaxation of N spheres;
// -1 if it never stops within 20 tau.
long stopping_sweep(const Relaxation &r, StopRule rule, long n, std::uint64_t seed)
{
  std::mt19937_64 bits(seed);
  const long cap = static_cast<long>(20 * r.tau);
  double z = r.z_inf + r.amplitude;
  ConvergenceCheck check(rule, r.eta, cap, z, 1.0, defaults::kSettleDriftWindow,
                         defaults::kSettleDriftConfidence);
  for (long s = 1; s <= cap; ++s) {
    const double mean = r.amplitude / r.tau * std::exp(-(s - 0.5) / r.tau);
    z -= mean + std::sqrt(mean * r.noise_b / static_cast<double>(n)) * gaussian(bits);
    const ConvergenceCheck::Verdict v = check.after_check(z, 1, 100);  // 1 % accepted
    if (v == ConvergenceCheck::Verdict::Converged) return s;
    if (v == ConvergenceCheck::Verdict::HitCap) return -1;
  }
  return -1;
}

}  // namespace

// Noise of amplitude 1/sqrt(N) around the same relaxation: the Drift rule stops at the crossing
// of the mean drift (within -3 % / +6 %: the window's standard errors delay it a little in the
// smallest packing) at every N from 1024 to 409600; the paper's Change rule stops at the first
// lucky sweep, 30 % early at N = 1024 and close to the crossing only at large N.
TEST(StopRule, DriftStopsAtTheSameSweepAtEveryNChangeDoesNot)
{
  const Relaxation r;
  const double crossing = r.crossing();  // 4962 sweeps
  const long sizes[] = {1024, 4096, 65536, 409600};
  const int seeds = 5;
  double change_mean[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    for (int seed = 0; seed < seeds; ++seed) {
      const long drift = stopping_sweep(r, StopRule::Drift, sizes[k], 1000 + seed);
      EXPECT_GT(drift, 0.97 * crossing) << "N " << sizes[k] << " seed " << seed;
      EXPECT_LT(drift, 1.06 * crossing) << "N " << sizes[k] << " seed " << seed;
      const long change = stopping_sweep(r, StopRule::Change, sizes[k], 1000 + seed);
      EXPECT_GT(change, 0) << "N " << sizes[k] << " seed " << seed;
      change_mean[k] += static_cast<double>(change) / seeds;
    }
  }
  EXPECT_LT(change_mean[0], 0.75 * crossing);
  EXPECT_GT(change_mean[3], 0.95 * crossing);
  for (int k = 1; k < 4; ++k) EXPECT_GT(change_mean[k], change_mean[k - 1]) << "N " << sizes[k];
}

// Without noise the Drift rule sees the exact mean decrement: it stops at the first check whose
// window mean (the drift at the window's middle) is below eta <Z>, and never before the window
// is full.
TEST(StopRule, DriftWithoutNoiseStopsWhereTheWindowMeanCrossesEta)
{
  Relaxation r;
  const long window = defaults::kSettleDriftWindow;
  double z = r.z_inf + r.amplitude;
  ConvergenceCheck check(StopRule::Drift, r.eta, 100000, z, 1.0, window, 2.0);
  std::vector<double> series{z};
  long stopped = -1;
  for (long s = 1; s <= 100000 && stopped < 0; ++s) {
    z = r.z_inf + r.amplitude * std::exp(-s / r.tau);
    series.push_back(z);
    if (check.after_check(z, 0, 100) == ConvergenceCheck::Verdict::Converged) stopped = s;
  }
  ASSERT_GT(stopped, window);
  auto window_mean = [&](long s) { return (series[s - window] - series[s]) / window; };
  // The standard error of an exponential's decrements is not zero but tiny next to the mean.
  EXPECT_LT((window_mean(stopped) + 2.0 * check.drift_standard_error()) / series[stopped], r.eta);
  EXPECT_GE(window_mean(stopped - 1) / series[stopped - 1], 0.99 * r.eta);
  EXPECT_NEAR(check.drift_per_sweep(), window_mean(stopped), 1e-15);
  // The window mean is the drift at the window's middle: the stop comes window/2 sweeps after
  // the crossing, plus tau ln(1 + 2 SE / mean) ~ 3 sweeps for the decrements' spread
  // (exp(window / tau) - 1 ~ 3 % across the window).
  EXPECT_NEAR(static_cast<double>(stopped), r.crossing() + window / 2.0 + 3.0, 2.0);

  // A constant <Z> from the start: Change stops at the first check, Drift only when the window
  // is full; both refuse while the packing falls freely (every trial accepted).
  ConvergenceCheck change(StopRule::Change, r.eta, 1000, 5.0, 1.0, window, 2.0);
  EXPECT_EQ(change.after_check(5.0, 0, 100), ConvergenceCheck::Verdict::Converged);
  ConvergenceCheck drift(StopRule::Drift, r.eta, 1000, 5.0, 1.0, window, 2.0);
  for (long c = 1; c < window; ++c)
    ASSERT_EQ(drift.after_check(5.0, 0, 100), ConvergenceCheck::Verdict::Continue) << c;
  EXPECT_EQ(drift.after_check(5.0, 100, 100), ConvergenceCheck::Verdict::Continue);
  EXPECT_EQ(drift.after_check(5.0, 0, 100), ConvergenceCheck::Verdict::Converged);
  EXPECT_EQ(drift.checks(), window + 1);
}

// The drift is per sweep whatever the check interval: checks of 4 sweeps see 4 times the change
// of <Z> per check, and the same relaxation stops at the same sweep (to within one check).
TEST(StopRule, DriftIsPerSweepWhateverTheCheckInterval)
{
  const Relaxation r;
  auto stop_sweep = [&](long sweeps_per_check) {
    double z = r.z_inf + r.amplitude;
    ConvergenceCheck check(StopRule::Drift, r.eta, 100000, z, static_cast<double>(sweeps_per_check),
                           8, 0.0);
    for (long c = 1; c < 100000; ++c) {
      z = r.z_inf + r.amplitude * std::exp(-static_cast<double>(c * sweeps_per_check) / r.tau);
      if (check.after_check(z, 0, 100) == ConvergenceCheck::Verdict::Converged)
        return c * sweeps_per_check;
    }
    return -1L;
  };
  const long one = stop_sweep(1), four = stop_sweep(4);
  // window 8 checks: centred 4 sweeps back with checks of one sweep, 16 with checks of four
  EXPECT_NEAR(static_cast<double>(one), r.crossing() + 4.0, 2.0);
  EXPECT_NEAR(static_cast<double>(four), r.crossing() + 16.0, 5.0);
}

// Settler::make_convergence_check (what settle and a decomposed driver use) builds the rule of
// the parameters: check every 4 sweeps of 100 spheres = drift per sweep of a quarter of the
// change per check.
TEST(StopRule, MadeFromTheSettleParameters)
{
  const Relaxation r;
  SettleParams p = paper_params(0.5, 1, 1, r.eta, 100000);
  p.stop = StopRule::Drift;
  p.drift_window = 8;
  p.check_interval = 400;
  ConvergenceCheck made = Settler::make_convergence_check(p, 100, r.z_inf + r.amplitude);
  ConvergenceCheck manual(StopRule::Drift, r.eta, 100000, r.z_inf + r.amplitude, 4.0, 8,
                          defaults::kSettleDriftConfidence);
  for (long c = 1; c < 100000; ++c) {
    const double z = r.z_inf + r.amplitude * std::exp(-4.0 * static_cast<double>(c) / r.tau);
    const auto a = made.after_check(z, 1, 400);
    ASSERT_EQ(a, manual.after_check(z, 1, 400)) << c;
    ASSERT_DOUBLE_EQ(made.drift_per_sweep(), manual.drift_per_sweep());
    if (a != ConvergenceCheck::Verdict::Continue) break;
  }
  EXPECT_GT(made.checks(), 8);
  EXPECT_THROW(Settler::make_convergence_check(p, 0, 1.0), std::invalid_argument);
}

// The paper's rule through both constructors: the same verdicts on the same series.
TEST(StopRule, ChangeRuleIsTheSameThroughBothConstructors)
{
  ConvergenceCheck legacy(1e-3, 50, 10.0);
  ConvergenceCheck general(StopRule::Change, 1e-3, 50, 10.0, 1.0, 32, 2.0);
  double z = 10.0;
  for (int c = 0; c < 60; ++c) {
    z -= 0.1 * std::exp(-0.2 * c);
    const long accepted = c % 7 == 0 ? 60 : 3;
    const auto a = legacy.after_check(z, accepted, 100);
    const auto b = general.after_check(z, accepted, 100);
    ASSERT_EQ(a, b) << c;
    if (a != ConvergenceCheck::Verdict::Continue) break;
  }
  EXPECT_EQ(legacy.checks(), general.checks());
}

// A stop of the paper's rule at a check that accepted no trial is flagged (<Z> did not move by
// chance); a stop with accepted trials is not, nor any stop of the Drift rule, whose window
// averages an idle check with the others.
TEST(StopRule, ChangeRuleFlagsAStopAtAnIdleCheck)
{
  ConvergenceCheck idle(1e-3, 50, 10.0);
  EXPECT_EQ(idle.after_check(9.0, 40, 100), ConvergenceCheck::Verdict::Continue);
  EXPECT_FALSE(idle.stopped_on_idle_check());
  EXPECT_EQ(idle.after_check(9.0, 0, 100), ConvergenceCheck::Verdict::Converged);
  EXPECT_TRUE(idle.stopped_on_idle_check());

  ConvergenceCheck moving(1e-3, 50, 10.0);
  EXPECT_EQ(moving.after_check(9.0, 40, 100), ConvergenceCheck::Verdict::Continue);
  EXPECT_EQ(moving.after_check(8.9999, 2, 100), ConvergenceCheck::Verdict::Converged);
  EXPECT_FALSE(moving.stopped_on_idle_check());

  ConvergenceCheck drift(StopRule::Drift, 1e-3, 50, 10.0, 1.0, 2, 0.0);
  ConvergenceCheck::Verdict v = ConvergenceCheck::Verdict::Continue;
  for (int c = 0; c < 3 && v == ConvergenceCheck::Verdict::Continue; ++c)
    v = drift.after_check(10.0, 0, 100);
  EXPECT_EQ(v, ConvergenceCheck::Verdict::Converged);
  EXPECT_FALSE(drift.stopped_on_idle_check());
}

// In the kernel, a bed of 16 spheres checked every sweep (16 trials): one accepted move changes
// <Z> by far more than eta = 1e-7, so the paper's rule only stops at a check that accepts
// nothing, and the result says so; the stop is then the same at eta = 1e-9 (same moves, same
// bed). The Drift rule, which stops by eta, is not flagged.
TEST(StopRule, KernelReportsAStopAtAnIdleCheck)
{
  Scene s = settled_bed(16, 2.0, 0.5, true, false, 5, 300);
  Settler settler;
  for (int tap = 0; tap < 5; ++tap) {
    dilate(s, 0.01);
    Scene tighter = s;
    SettleParams p = paper_params(0.5, 1, 9 + static_cast<std::uint64_t>(tap), 1e-7, 10000);
    const SettleResult res =
        settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    EXPECT_TRUE(res.stopped_on_idle_check) << tap;
    p.eta = 1e-9;
    const SettleResult same = settler.settle(tighter.xyz.data(), tighter.radius.data(), nullptr,
                                             tighter.size(), tighter.box, p);
    EXPECT_TRUE(same.stopped_on_idle_check) << tap;
    EXPECT_EQ(same.trials, res.trials) << tap;
    EXPECT_EQ(tighter.xyz, s.xyz) << tap;

    Scene drifting = tighter;
    p.stop = StopRule::Drift;
    p.eta = 1e-3;
    p.drift_window = 4;
    const SettleResult drift = settler.settle(drifting.xyz.data(), drifting.radius.data(),
                                              nullptr, drifting.size(), drifting.box, p);
    EXPECT_FALSE(drift.hit_cap) << tap;
    EXPECT_FALSE(drift.stopped_on_idle_check) << tap;
  }
}

// In the kernel: 'stop drift' on a tapped bed converges, after at least a full window of
// checks, to a valid packing; a window longer than the cap ends at the cap; the window is
// validated.
TEST(StopRule, KernelDriftRuleConvergesAfterAFullWindow)
{
  Scene s = settled_bed(512, 8.0, 0.5, true, false, 61, 300);
  dilate(s, 0.01);
  Scene copy = s;
  Settler settler;
  SettleParams p = paper_params(0.5, 1, 77, 1e-4, 10000);
  p.stop = StopRule::Drift;
  p.drift_window = 8;
  const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
  EXPECT_FALSE(res.hit_cap);
  EXPECT_GE(res.checks, 8);
  EXPECT_LT(res.mean_height, res.mean_height_start);
  const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), s.size(), s.box,
                                              defaults::kContactTolerance);
  EXPECT_EQ(v.i, -1);

  // a window beyond the cap could never stop before it: refused before anything moves
  p.drift_window = 40;
  p.max_checks = 20;
  const std::vector<double> before = copy.xyz;
  EXPECT_THROW(settler.settle(copy.xyz.data(), copy.radius.data(), nullptr, copy.size(), copy.box, p),
               std::invalid_argument);
  EXPECT_EQ(copy.xyz, before);

  for (long bad : {1L, 0L, -3L, defaults::kSettleDriftWindowMax + 1}) {
    p.drift_window = bad;
    EXPECT_THROW(Settler::validate(p), std::invalid_argument) << bad;
  }
}
