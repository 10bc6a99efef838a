// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Cost of the four laws of theta (fix mc/settle theta_law: eq. 1 per unit angle, eq. 1 per
// unit solid angle, section II's exponential and linear laws), each against eq. 1's angle law
// measured in the same run:
//   1. the move generation alone: batched draws (TrialMoveSampler::draw_batch, as the trial
//      loop makes them), CPU ns per trial at theta0 = pi/16, pi/4, pi/2;
//   2. a whole redeposition: a settled bed (N = 4096, L = 32R, PBC) tapped once at the paper's
//      eps = 0.0225 and settled until eta = 1e-6 under each law at theta0 = pi/16, pi/4, pi/2:
//      sweeps, acceptance, M moves per CPU second and CPU seconds per redeposition.
// A law's sweeps to converge are physics (wider or narrower moves settle at another pace), its
// M moves/s the kernel's price; CPU s per redeposition is what a user pays.
//
// Usage: bench_theta_laws [--quick]   (about 40 s of one core; --quick about 10 s)
// Separate from bench_mc_settle because bench/ab_mc_settle.py compiles that program against
// older kernels, which lack the exponential and linear laws.
#include "bench_common.h"
#include "../tests/unit/settle_test_scenes.h"
#include "tapmc_math.h"
#include "tapmc_settle.h"
#include "tapmc_trial_move.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;

using tapmc_bench::cpu_model;
using tapmc_bench::median;
using tapmc_bench::thread_cpu_seconds;

namespace {

struct Law {
  ThetaLaw law;
  const char *name;
};
constexpr Law kLaws[] = {{ThetaLaw::Angle, "angle (eq. 1)"},
                         {ThetaLaw::Solid, "solid (eq. 1)"},
                         {ThetaLaw::Exponential, "exponential"},
                         {ThetaLaw::Linear, "linear"}};
constexpr double kWidthsOverPi[] = {1.0 / 16, 1.0 / 4, 1.0 / 2};

// Median CPU ns per trial of batched draws (n_trials per repeat).
double draw_ns(ThetaLaw law, double theta0, int n_trials, int repeats)
{
  const TrialMoveSampler sampler(0.2, theta0, law);
  const CounterRandom rng(1, 2);
  std::vector<TrialDraw> buf(TrialMoveSampler::kBatchMax);
  std::vector<double> ns;
  double sink = 0;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = thread_cpu_seconds();
    for (int k = 0; k < n_trials; k += TrialMoveSampler::kBatchMax) {
      sampler.draw_batch(rng, static_cast<std::uint64_t>(r) * n_trials + k,
                         TrialMoveSampler::kBatchMax, 4096, buf.data());
      sink += buf[k % TrialMoveSampler::kBatchMax].move.dz;
    }
    ns.push_back((thread_cpu_seconds() - t0) / n_trials * 1e9);
  }
  if (sink == 42.0) std::printf(" ");  // keeps the draws from being optimised away
  return median(ns);
}

struct Redeposition {
  double cpu_s = 0, moves_per_s = 0, acceptance = 0;
  long sweeps = 0;
};

// One redeposition of `tapped` until eta under the law (median CPU time of `repeats` streams;
// sweeps and acceptance of the median run).
Redeposition redeposit(Settler &settler, const Scene &tapped, ThetaLaw law, double theta0,
                       double eta, int repeats)
{
  std::vector<Redeposition> runs;
  for (int r = 0; r < repeats; ++r) {
    Scene s = tapped;
    SettleParams p = paper_params(1.0, 31, 200 + r, eta, 100000);
    p.theta_law = law;
    p.theta0 = theta0;
    const double t0 = thread_cpu_seconds();
    const SettleResult res =
        settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    Redeposition d;
    d.cpu_s = thread_cpu_seconds() - t0;
    d.moves_per_s = res.trials / d.cpu_s;
    d.acceptance = static_cast<double>(res.accepted) / res.trials;
    d.sweeps = res.checks;
    runs.push_back(d);
  }
  std::sort(runs.begin(), runs.end(),
            [](const Redeposition &a, const Redeposition &b) { return a.cpu_s < b.cpu_s; });
  return runs[runs.size() / 2];
}

}  // namespace

int main(int argc, char **argv)
{
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 2 || (argc == 2 && !quick)) {
    std::fprintf(stderr, "usage: bench_theta_laws [--quick] (got '%s')\n", argv[argc - 1]);
    return 1;
  }
  std::printf("bench_theta_laws on %s%s\n", cpu_model().c_str(), quick ? " (--quick)" : "");

  // 1. Move generation.
  const int n_trials = quick ? 1 << 19 : 1 << 21, repeats = quick ? 3 : 5;
  std::printf("\nmove generation (batched draws, CPU ns per trial; ratio = law / angle law at the "
              "same theta0):\n%-16s", "law");
  for (double w : kWidthsOverPi) std::printf("   theta0 = pi/%-3g ratio", 1.0 / w);
  std::printf("\n");
  double angle_ns[3] = {0, 0, 0};
  for (const Law &law : kLaws) {
    std::printf("%-16s", law.name);
    for (int k = 0; k < 3; ++k) {
      const double ns = draw_ns(law.law, kWidthsOverPi[k] * kPi, n_trials, repeats);
      if (law.law == ThetaLaw::Angle) angle_ns[k] = ns;
      std::printf("   %10.2f ns %7.3f", ns, ns / angle_ns[k]);
    }
    std::printf("\n");
  }

  // 2. A redeposition after a tap.
  const double eta = 1e-6, eps = 0.0225;
  std::printf("\nredeposition after a tap eps = %g until eta = %g (N = 4096, L = 32R, PBC, settled "
              "bed;\n  median CPU time of %d streams; ratio = CPU s / angle law's at the same "
              "theta0):\n",
              eps, eta, quick ? 1 : 3);
  std::printf("%-10s %-16s %7s %8s %10s %9s %7s\n", "theta0", "law", "sweeps", "accept.",
              "M moves/s", "CPU s", "ratio");
  Scene tapped = settled_bed(4096, 32.0, 1.0, true, false, 7, quick ? 100 : 400);
  dilate(tapped, eps);
  Settler settler;
  redeposit(settler, tapped, ThetaLaw::Angle, kPi / 4, 1e-3, 1);  // warm-up: storage, caches
  for (double w : kWidthsOverPi) {
    double angle_s = 0;
    for (const Law &law : kLaws) {
      const Redeposition d = redeposit(settler, tapped, law.law, w * kPi, eta, quick ? 1 : 3);
      if (law.law == ThetaLaw::Angle) angle_s = d.cpu_s;
      std::printf("pi/%-7g %-16s %7ld %8.4f %10.2f %9.3f %7.3f\n", 1.0 / w, law.name, d.sweeps,
                  d.acceptance, d.moves_per_s / 1e6, d.cpu_s, d.cpu_s / angle_s);
    }
  }
  return 0;
}
