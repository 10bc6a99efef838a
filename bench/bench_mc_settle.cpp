// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Benchmark of the redeposition kernel: trial moves per second on the paper's scene, against a
// naive all-pairs loop making the same moves; sweep order, poly, FBC, large N; theta sampler
// cost; sweeps per redeposition versus eta.
//
// Usage: bench_mc_settle [--quick]   (--quick: fewer repeats, no N = 32768)
#include "bench_common.h"
#include "../tests/unit/settle_test_scenes.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_settle.h"
#include "tapmc_trial_move.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;
using Clock = std::chrono::steady_clock;

using tapmc_bench::cpu_model;
using tapmc_bench::median;
using tapmc_bench::seconds_since;

namespace {




// The paper's initial state: Jullien-Meakin sequential deposition (phi ~ 0.58), R = 1.
Scene deposited_bed(int n, double side, bool periodic, bool poly, std::uint64_t seed)
{
  DepositionDomain dom;
  dom.xhi = dom.yhi = side;
  dom.periodic_x = dom.periodic_y = periodic;
  const RadiusDistribution radii =
      poly ? RadiusDistribution::uniform(0.8, 1.0) : RadiusDistribution::monodisperse(1.0);
  Packing pk = deposit_packing(n, radii, dom, seed);
  Scene s;
  s.xyz = pk.xyz;
  s.radius = pk.radius;
  s.box = make_box(side, periodic);
  return s;
}

struct Rate {
  double moves_per_s, acceptance;
};

// Median trial moves per second of `sweeps` sweeps (no eta stop) from the same start.
Rate time_settler(const Scene &start, PickOrder order, long sweeps, int repeats)
{
  std::vector<double> rates;
  double acc = 0;
  Settler settler;
  for (int r = 0; r < repeats; ++r) {
    Scene s = start;
    SettleParams p = paper_params(1.0, 12345, 1000 + r, 1e-300, sweeps);
    p.order = order;
    const Clock::time_point t0 = Clock::now();
    const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    rates.push_back(res.trials / seconds_since(t0));
    acc = static_cast<double>(res.accepted) / res.trials;
  }
  return {median(rates), acc};
}

// The naive reference: same random stream and moves, overlap test against all n spheres with
// all periodic images (O(N) per trial). Returns moves per second; positions left in s.
double time_naive(Scene &s, std::uint64_t stream, long trials)
{
  const int n = s.size();
  const TrialMoveSampler sampler(0.2, defaults::kThetaWidth);
  const CounterRandom rng(12345, stream);
  const double side = s.box.hi[0] - s.box.lo[0], tol = defaults::kContactTolerance;
  const Clock::time_point t0 = Clock::now();
  for (long t = 0; t < trials; ++t) {
    const TrialDraw d = sampler.draw(rng, t, n);
    const int i = d.pick;
    const double r = s.radius[i];
    double x = s.xyz[3 * i] + d.move.dx, y = s.xyz[3 * i + 1] + d.move.dy;
    const double z = s.xyz[3 * i + 2] + d.move.dz;
    if (x < 0) x += side;
    if (x >= side) x -= side;
    if (y < 0) y += side;
    if (y >= side) y -= side;
    if (gap_violates(floor_gap(z, r, 0.0), r, tol)) continue;
    bool overlap = false;
    for (int j = 0; j < n && !overlap; ++j) {
      if (j == i) continue;
      double dx = s.xyz[3 * j] - x, dy = s.xyz[3 * j + 1] - y;
      dx -= side * std::round(dx / side);
      dy -= side * std::round(dy / side);
      const double dz = s.xyz[3 * j + 2] - z;
      overlap = dx * dx + dy * dy + dz * dz < overlap_threshold_sq(r, s.radius[j], 1 - tol);
    }
    if (overlap) continue;
    s.xyz[3 * i] = x;
    s.xyz[3 * i + 1] = y;
    s.xyz[3 * i + 2] = z;
  }
  return trials / seconds_since(t0);
}

}  // namespace

int main(int argc, char **argv)
{
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress visible when redirected
  const int repeats = quick ? 3 : 5;
  const long sweeps = quick ? 20 : 50;
  std::printf("bench_mc_settle: TAPMC redeposition kernel\n");
  std::printf("machine: %s (one core)\n", cpu_model().c_str());
  std::printf("scene: N = 4096, L = 32R, PBC, Jullien-Meakin bed, d_max = R/5, theta0 = pi/4\n\n");

  // The deposited bed is stable under downward single-sphere moves (every sphere rests on
  // three supports: acceptance 0); the timed workload is that bed just after a tap eps = 0.01,
  // run for a fixed number of sweeps.
  const Scene deposited = deposited_bed(4096, 32.0, true, false, 7);
  std::printf("bed: phi(2R..20R) = %.4f, phi_b(0..4R) = %.4f\n", slab_fraction(deposited, 2, 20),
              slab_fraction(deposited, 0, 4));
  Scene bed = deposited;
  dilate(bed, 0.01);
  const Rate still = time_settler(deposited, PickOrder::Random, sweeps, repeats);
  std::printf("%-44s %10.2f M moves/s  (acceptance %.3f)\n", "Settler, deposited bed before the tap",
              still.moves_per_s / 1e6, still.acceptance);

  // 1. Paper scene, Random order, against the naive loop on the same moves.
  const Rate fast = time_settler(bed, PickOrder::Random, sweeps, repeats);
  Scene naive_scene = bed, kernel_scene = bed;
  const long naive_trials = quick ? 20000 : 4096 * 10;
  std::vector<double> naive_rates;
  for (int r = 0; r < (quick ? 1 : 3); ++r) {
    naive_scene = bed;
    naive_rates.push_back(time_naive(naive_scene, 1000, naive_trials));
  }
  {
    // Same moves through the kernel: positions must agree with the naive loop.
    Settler settler;
    SettleParams p = paper_params(1.0, 12345, 1000, 1e-300, 1);
    p.check_interval = naive_trials;
    settler.settle(kernel_scene.xyz.data(), kernel_scene.radius.data(), nullptr, 4096, kernel_scene.box, p);
  }
  long differ = 0;
  for (std::size_t k = 0; k < bed.xyz.size(); ++k) differ += kernel_scene.xyz[k] != naive_scene.xyz[k];
  const double naive = median(naive_rates);
  std::printf("\n%-44s %10.2f M moves/s  (acceptance %.3f)\n", "Settler, Random order (paper)",
              fast.moves_per_s / 1e6, fast.acceptance);
  std::printf("%-44s %10.3f M moves/s\n", "naive all-pairs loop, same moves", naive / 1e6);
  std::printf("%-44s %10.1f x   (%ld coordinates differ after %ld trials)\n", "ratio",
              fast.moves_per_s / naive, differ, naive_trials);

  // 2. Variants.
  const Rate sweep = time_settler(bed, PickOrder::Sweep, sweeps, repeats);
  std::printf("%-44s %10.2f M moves/s  (acceptance %.3f)\n", "Settler, Sweep order", sweep.moves_per_s / 1e6,
              sweep.acceptance);
  Scene poly = deposited_bed(4096, 32.0, true, true, 7);
  dilate(poly, 0.01);
  const Rate poly_rate = time_settler(poly, PickOrder::Random, sweeps, repeats);
  std::printf("%-44s %10.2f M moves/s  (acceptance %.3f)\n", "Settler, polydisperse R in [0.8, 1]",
              poly_rate.moves_per_s / 1e6, poly_rate.acceptance);
  Scene walls = deposited_bed(4096, 32.0, false, false, 7);
  dilate(walls, 0.01);
  const Rate fbc = time_settler(walls, PickOrder::Random, sweeps, repeats);
  std::printf("%-44s %10.2f M moves/s  (acceptance %.3f)\n", "Settler, FBC (walls)", fbc.moves_per_s / 1e6,
              fbc.acceptance);
  {
    // The redeposition workload: a tap eps = 0.01 of the bed, until eta = 1e-4.
    std::vector<double> rates;
    for (int r = 0; r < repeats; ++r) {
      Scene s = bed;
      Settler settler;
      const Clock::time_point t0 = Clock::now();
      const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box,
                                              paper_params(1.0, 99, 2000 + r, 1e-6, 100000));
      rates.push_back(res.trials / seconds_since(t0));
    }
    std::printf("%-44s %10.2f M moves/s\n", "Settler, same, until eta = 1e-6", median(rates) / 1e6);
  }
  if (!quick) {
    Scene big = deposited_bed(32768, 32.0 * std::sqrt(8.0), true, false, 7);
    dilate(big, 0.01);
    const Rate big_random = time_settler(big, PickOrder::Random, 10, 3);
    const Rate big_sweep = time_settler(big, PickOrder::Sweep, 10, 3);
    std::printf("%-44s %10.2f M moves/s\n", "Settler, N = 32768 (L = 90.5R), Random", big_random.moves_per_s / 1e6);
    std::printf("%-44s %10.2f M moves/s\n", "Settler, N = 32768 (L = 90.5R), Sweep", big_sweep.moves_per_s / 1e6);
  }

  // 3. Cost of the move generation alone.
  {
    const TrialMoveSampler sampler(0.2, defaults::kThetaWidth);
    const CounterRandom rng(1, 2);
    const int n = 4000000;
    double sink = 0;
    Clock::time_point t0 = Clock::now();
    std::uint64_t extra = 1ull << 40;  // fresh words for the rare rejections
    for (int k = 0; k < n; ++k) {
      const RandomBlock w = rng.block(k);
      bool first = true;
      sink += sampler.theta_sampler().sample(w[0], [&](std::uint32_t &p, std::uint32_t &u) {
        if (first) {
          p = w[1];
          u = w[2];
          first = false;
        } else {
          const RandomBlock more = rng.block(extra++);
          p = more[0];
          u = more[1];
        }
      });
    }
    const double theta_ns = seconds_since(t0) / n * 1e9;
    t0 = Clock::now();
    for (int k = 0; k < n; ++k) sink += rng.block(k)[0];
    const double block_ns = seconds_since(t0) / n * 1e9;
    t0 = Clock::now();
    for (int k = 0; k < n; ++k) sink += sampler.draw(rng, k, 4096).move.dz;
    const double draw_ns = seconds_since(t0) / n * 1e9;
    std::vector<TrialDraw> buf(TrialMoveSampler::kBatchMax);
    t0 = Clock::now();
    for (int k = 0; k < n; k += TrialMoveSampler::kBatchMax) {
      sampler.draw_batch(rng, k, TrialMoveSampler::kBatchMax, 4096, buf.data());
      sink += buf[0].move.dz;
    }
    const double batch_ns = seconds_since(t0) / n * 1e9;
    std::printf("\nmove generation: theta sample (one Philox block incl.) %.1f ns, Philox block %.1f ns,\n"
                "  full draw %.1f ns, batched draw %.1f ns per trial; exp needed in %.1f %% of theta samples\n",
                theta_ns, block_ns, draw_ns, batch_ns, 100 * sampler.theta_sampler().exp_fraction());
    if (sink == 42.0) std::printf(" ");
  }

  // 4. Sweeps per redeposition after a tap eps = 0.01 versus eta, on the deposited bed, and
  // the fraction of the tap's lift of <Z> the redeposition recovered.
  std::printf("\nredeposition after eps = 0.01 versus eta (N = 4096 PBC, deposited bed; mean of 3 taps):\n");
  for (double eta : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7}) {
    double sweeps_sum = 0, recovered = 0, secs = 0;
    const int taps = 3;
    for (int tap = 0; tap < taps; ++tap) {
      Scene s = bed;
      Settler settler;
      const Clock::time_point t0 = Clock::now();
      const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box,
                                              paper_params(1.0, 77, 10 + tap, eta, 20000));
      secs += seconds_since(t0);
      sweeps_sum += res.checks;
      const double before_tap = res.mean_height_start / 1.01;
      recovered += (res.mean_height_start - res.mean_height) / (res.mean_height_start - before_tap);
    }
    std::printf("  eta = %.0e: %8.1f sweeps, %7.3f s per tap, recovered %5.1f %% of the tap's <Z> lift\n",
                eta, sweeps_sum / taps, secs / taps, 100 * recovered / taps);
  }
  return 0;
}
