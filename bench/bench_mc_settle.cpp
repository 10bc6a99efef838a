// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Benchmark of the redeposition kernel: trial moves per second on the paper's scene, against a
// naive all-pairs loop making the same moves; sweep order, poly, FBC; theta sampler cost;
// sweeps per redeposition versus eta; scaling with N (4096, 32768, 262144) on a first and a
// second tap, with list lengths, local list updates per sweep and peak memory, and the locality
// ceiling (the same sweeps in memory order).
//
// Usage: bench_mc_settle [--quick] [--scaling | --kernel]
//   --quick:   fewer repeats and sweeps, scaling for N = 4096 and 262144 only (under 2 min)
//   --kernel:  only the kernel rows, one line each (the rows bench/ab_mc_settle.py alternates
//              with a reference commit): N = 4096 Random / Sweep / poly / FBC and a tap until
//              eta = 1e-6 (about 3 s); with --large also the first tap of N = 262144 (+ 10 s)
//   --scaling: only the scaling section
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
#include <map>
#include <string>
#include <sys/resource.h>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;
using Clock = std::chrono::steady_clock;

using tapmc_bench::cpu_model;
using tapmc_bench::median;
using tapmc_bench::seconds_since;
using tapmc_bench::thread_cpu_seconds;

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

// Peak resident memory of this process so far, MB.
double peak_rss_mb()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux: kB
}

struct TapRate {
  double moves_per_s = 0, list_length = 0, updates_per_sweep = 0, acceptance = 0;
  long sweeps = 0, widenings = 0;
};

// One redeposition of `start` (Random order): until eta, or `sweeps` sweeps when eta is 0,
// timed in CPU seconds of this thread (the machine is shared). The settled positions are left
// in `out` when given.
TapRate time_tap(Settler &settler, const Scene &start, double eta, long sweeps,
                 std::uint64_t stream, Scene *out = nullptr, PickOrder order = PickOrder::Random)
{
  Scene s = start;
  SettleParams p = paper_params(1.0, 31, stream, eta > 0 ? eta : 1e-300, sweeps);
  p.order = order;
  const double t0 = thread_cpu_seconds();
  const SettleResult res =
      settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
  const double secs = thread_cpu_seconds() - t0;
  TapRate r;
  r.moves_per_s = res.trials / secs;
  r.list_length = res.mean_list_length;
  r.sweeps = res.checks;
  r.updates_per_sweep = static_cast<double>(res.list_updates) / res.checks;
  r.acceptance = static_cast<double>(res.accepted) / res.trials;
  r.widenings = res.list_widenings;
  if (out) *out = s;
  return r;
}

// Scaling with N at the paper's height (N / L^2 = 4 / R^2 as for N = 4096, L = 32R): a
// Jullien-Meakin bed tapped once (eps = 0.01) and, after settling to eta = 1e-5, tapped again.
// One Settler per N, as fix mc/settle keeps one for the whole run (storage reused between
// calls), warmed up by one untimed sweep.
void scaling_section(bool quick)
{
  std::printf("\nscaling (PBC, R = 1, N / L^2 = 4 as for N = 4096 at L = 32R; Random order; eps = 0.01;\n"
              "  M moves per CPU second of this thread, the list build of each call included;\n"
              "  'first': the deposited bed tapped once, 'second': that tap settled to eta = 1e-5 and\n"
              "  tapped again; 'fixed': %d sweeps, 'eta': until eta = 1e-5):\n", quick ? 20 : 100);
  std::printf("%7s %6s %-7s %-6s %7s %9s %8s %11s %10s\n", "N", "L/R", "tap", "run", "sweeps",
              "M moves/s", "list len", "upd./sweep", "accept.");
  const long fixed = quick ? 20 : 100;
  std::vector<int> sizes = {4096, 32768, 262144};
  if (quick) sizes = {4096, 262144};
  double rate_4096[4] = {0, 0, 0, 0};
  std::map<int, std::pair<double, double>> locality;  // N -> (Random, Sweep) moves/s, first fixed
  for (int n : sizes) {
    const double side = 32.0 * std::sqrt(n / 4096.0);
    Scene first = deposited_bed(n, side, true, false, 7);
    dilate(first, 0.01);
    Scene settled;
    TapRate rates[4];
    Settler settler;
    time_tap(settler, first, 0.0, 1, 499);
    rates[0] = time_tap(settler, first, 0.0, fixed, 500);
    rates[1] = time_tap(settler, first, 1e-5, 50000, 501, &settled);
    Scene second = settled;
    dilate(second, 0.01);
    rates[2] = time_tap(settler, second, 0.0, fixed, 502);
    rates[3] = time_tap(settler, second, 1e-5, 50000, 503);
    // The locality ceiling: the same fixed sweeps in memory order (spheres are stored in
    // cell order), the best order any reordering of the picks could reach.
    locality[n] = {rates[0].moves_per_s,
                   time_tap(settler, first, 0.0, fixed, 504, nullptr, PickOrder::Sweep).moves_per_s};
    const char *tap[4] = {"first", "first", "second", "second"};
    const char *run[4] = {"fixed", "eta", "fixed", "eta"};
    for (int k = 0; k < 4; ++k) {
      if (n == 4096) rate_4096[k] = rates[k].moves_per_s;
      std::printf("%7d %6.1f %-7s %-6s %7ld %9.2f %8.1f %11.1f %10.4f", n, side, tap[k], run[k],
                  rates[k].sweeps, rates[k].moves_per_s / 1e6, rates[k].list_length,
                  rates[k].updates_per_sweep, rates[k].acceptance);
      if (rates[k].widenings) std::printf("  (%ld row widenings)", rates[k].widenings);
      if (n != 4096) std::printf("   ratio to N = 4096: %.2f", rates[k].moves_per_s / rate_4096[k]);
      std::printf("\n");
    }
    std::printf("%7s peak RSS so far: %.0f MB\n", "", peak_rss_mb());
  }
  std::printf("\nlocality ceiling ('first', 'fixed'; Sweep order visits the spheres in memory order,\n"
              "  which is cell order, so it bounds what processing picks in cell order could gain):\n");
  std::printf("%7s %16s %15s %14s %18s %18s\n", "N", "Random M moves/s", "Sweep M moves/s",
              "Sweep / Random", "Random / N = 4096", "Sweep / N = 4096");
  const std::pair<double, double> base = locality[4096];
  for (const auto &[n, rate] : locality)
    std::printf("%7d %16.2f %15.2f %14.2f %18.2f %18.2f\n", n, rate.first / 1e6, rate.second / 1e6,
                rate.second / rate.first, rate.first / base.first, rate.second / base.second);
}

// The kernel rows alone, one "label  value M moves/s" line each, medians of CPU-timed repeats
// (bench/ab_mc_settle.py reads them).
void kernel_section(bool large)
{
  // 100 sweeps a repeat: the list build of each call stays near 1 % of the row
  const int repeats = 3;
  const long sweeps = 100;
  const Scene deposited = deposited_bed(4096, 32.0, true, false, 7);
  Scene bed = deposited;
  dilate(bed, 0.01);
  Scene poly = deposited_bed(4096, 32.0, true, true, 7);
  dilate(poly, 0.01);
  Scene walls = deposited_bed(4096, 32.0, false, false, 7);
  dilate(walls, 0.01);
  Settler settler;
  auto row = [&](const char *label, const Scene &start, double eta, long max_sweeps,
                 PickOrder order) {
    std::vector<double> rates;
    time_tap(settler, start, 0.0, 1, 99, nullptr, order);  // warm-up: storage and caches
    for (int r = 0; r < repeats; ++r)
      rates.push_back(time_tap(settler, start, eta, max_sweeps, 100 + r, nullptr, order).moves_per_s);
    std::printf("%-44s %10.3f M moves/s\n", label, median(rates) / 1e6);
  };
  row("N = 4096, Random order (paper)", bed, 0.0, sweeps, PickOrder::Random);
  row("N = 4096, Sweep order", bed, 0.0, sweeps, PickOrder::Sweep);
  row("N = 4096, polydisperse R in [0.8, 1]", poly, 0.0, sweeps, PickOrder::Random);
  row("N = 4096, FBC (walls)", walls, 0.0, sweeps, PickOrder::Random);
  row("N = 4096, a tap until eta = 1e-6", bed, 1e-6, 100000, PickOrder::Random);
  {
    // The move generation alone (batched draws, as the trial loop makes them).
    const TrialMoveSampler sampler(0.2, defaults::kThetaWidth);
    const CounterRandom rng(1, 2);
    std::vector<TrialDraw> buf(TrialMoveSampler::kBatchMax);
    std::vector<double> rates;
    double sink = 0;
    const int n = 1 << 21;
    for (int r = 0; r < repeats; ++r) {
      const double t0 = thread_cpu_seconds();
      for (int k = 0; k < n; k += TrialMoveSampler::kBatchMax) {
        sampler.draw_batch(rng, static_cast<std::uint64_t>(r) * n + k, TrialMoveSampler::kBatchMax,
                           4096, buf.data());
        sink += buf[k % TrialMoveSampler::kBatchMax].move.dz;
      }
      rates.push_back(n / (thread_cpu_seconds() - t0));
    }
    std::printf("%-44s %10.3f M moves/s  (draws only; %g)\n", "move generation, batched draws",
                median(rates) / 1e6, sink > 0 ? 1.0 : 0.0);
  }
  if (!large) return;
  Scene bed_large = deposited_bed(262144, 256.0, true, false, 7);
  dilate(bed_large, 0.01);
  Settler large_settler;
  std::vector<double> rates;
  time_tap(large_settler, bed_large, 0.0, 1, 99);
  for (int r = 0; r < 3; ++r)
    rates.push_back(time_tap(large_settler, bed_large, 0.0, 20, 100 + r).moves_per_s);
  std::printf("%-44s %10.3f M moves/s\n", "N = 262144, Random order, first tap", median(rates) / 1e6);
}

}  // namespace

int main(int argc, char **argv)
{
  bool quick = false, scaling_only = false, kernel_only = false, large = false;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[a], "--scaling") == 0) scaling_only = true;
    else if (std::strcmp(argv[a], "--kernel") == 0) kernel_only = true;
    else if (std::strcmp(argv[a], "--large") == 0) large = true;
    else {
      std::fprintf(stderr, "bench_mc_settle: unknown argument '%s' (allowed: --quick, "
                   "--scaling, --kernel [--large])\n", argv[a]);
      return 2;
    }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress visible when redirected
  if (kernel_only) {
    std::printf("bench_mc_settle: TAPMC redeposition kernel\nmachine: %s (one core)\n",
                cpu_model().c_str());
    kernel_section(large);
    return 0;
  }
  if (scaling_only) {
    std::printf("bench_mc_settle: TAPMC redeposition kernel\nmachine: %s (one core)\n",
                cpu_model().c_str());
    scaling_section(quick);
    return 0;
  }
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
    // The Philox blocks alone, batched as draw_batch computes them (two per trial): what a
    // cheaper generator could save at most.
    std::vector<std::uint64_t> positions(CounterRandom::kBatchMax);
    std::vector<RandomBlock> blocks(CounterRandom::kBatchMax);
    t0 = Clock::now();
    for (int k = 0; k < n; k += CounterRandom::kBatchMax) {
      for (int j = 0; j < CounterRandom::kBatchMax; ++j) positions[j] = std::uint64_t(k + j) * 7;
      rng.blocks(positions.data(), CounterRandom::kBatchMax, blocks.data());
      sink += blocks[0][0];
    }
    const double batch_block_ns = seconds_since(t0) / n * 1e9;
    std::printf("\nmove generation: theta sample (one Philox block incl.) %.1f ns, Philox block %.1f ns,\n"
                "  full draw %.1f ns, batched draw %.1f ns per trial (its two batched Philox\n"
                "  blocks %.1f ns); exp needed in %.1f %% of theta samples\n",
                theta_ns, block_ns, draw_ns, batch_ns, 2 * batch_block_ns,
                100 * sampler.theta_sampler().exp_fraction());
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
  scaling_section(quick);
  return 0;
}
