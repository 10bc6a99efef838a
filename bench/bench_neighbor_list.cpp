// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Benchmark behind the kernel's neighbour list: tapmc::Settler against Verlet neighbour lists
// with a skin (what LAMMPS would hand a fix) and a naive all-pairs loop, same trial moves.
//
// tapmc::Settler runs on tapmc::SphereMover (tapmc_sphere_mover.cpp): lists of the "lammps"
// radius (R_i + R_j) + d_max + skin, skin 0.2 R (defaults::kListSkinOverRadius), kept up to date
// per sphere (a sphere that moved skin/2 is relisted locally) instead of by global rebuilds.
// VerletRun here is the variant explorer (skins, rules, entry order; monodisperse PBC only),
// not a second production copy: it shows why the kernel uses this list radius and this skin.
//
// Result (AMD EPYC, one core of a shared 2-core machine, medians; bench/README.md): all methods
// accept exactly the same moves (40960 trials on the tapped bed and on a loose start with up to
// 23000 list rebuilds; positions within 4e-15 after a whole redeposition). Over a whole
// redeposition (1000 sweeps after the tap) a Verlet list owned by the kernel with the LAMMPS
// rule (list radius 2R + d_max + skin, rebuilt when a sphere has moved skin/2) makes 23.6 / 28.2
// / 26.2 / 22.9 M trial moves/s at skin 0.1 / 0.2 / 0.4 / 0.8 R (~440-530x the all-pairs loop,
// 0.05 M/s), rebuild cost included, with 0.030 / 0.006 / 0.002 / 0.001 builds per sweep (30 / 6
// / 2 / 1 builds per redeposition). The redeposition is a slow creep (2-3 % acceptance, accepted
// steps of order eps * 2R), so a list built once per tap almost never needs rebuilding, and it
// holds 8-10 candidates. The exact "trial" rule (skin 0.4R: 27.1 M/s) is no better than the
// LAMMPS rule; at skin = d_max it rebuilds ~50 times per sweep (0.05 M/s). Entry order
// (below-first) changes little. This is an idealised list owned by the kernel; LAMMPS' own
// lists would add ghost copies to update whenever a sphere near a periodic face moves, and a
// rebuild inside the fix would need LAMMPS' exchange/borders/reneighbour cycle: hence
// kernel-owned lists (skin 0.2R), not LAMMPS' lists.
//
// What is compared (N = 4096, R = 1, L = 32R, PBC, floor, Jullien-Meakin bed dilated by a tap
// eps = 0.01, d_max = R/5, theta0 = pi/4, seed/stream/trial-keyed draws of tapmc_trial_move.h,
// so every method makes the same trials in the same order):
//  - tapmc::Settler (production: "lammps" list radius, skin 0.2R, local upkeep), a fixed
//    number of sweeps (no eta stop);
//  - Verlet lists: full list per sphere (CSR, periodic image shift stored per entry, coordinates
//    left unwrapped between builds as LAMMPS does), built in O(N) by binning, each trial tests
//    the floor and the sphere's list only (early exit on the first overlap). Two exact
//    rebuild rules, because a Monte Carlo trial reaches d_max beyond the sphere's position:
//      "lammps": list radius 2R + d_max + skin (the reach of a trial is the "pair cutoff"),
//                rebuilt as soon as an accepted move leaves any sphere more than skin/2 from
//                its position at the build (LAMMPS' `neigh_modify every 1 delay 0 check yes`);
//      "trial":  list radius 2R + skin (skin >= d_max), rebuilt only when a trial could miss a
//                neighbour: |trial - r_i(build)| + max_j |r_j - r_j(build)| > skin.
//    Each with list entries in build order, or sorted "below first" (lower spheres first:
//    downward moves are blocked from below);
//  - all-pairs: every sphere, minimum image, early exit (the reference of the ratios).
// Exactness: the all-pairs loop does the Settler's arithmetic bit for bit; the Verlet runs
// use unwrapped coordinates, so positions agree to rounding (1e-9 is asserted) and the number
// of accepted moves must be equal.
//
// Usage: bench_neighbor_list [--quick]
#include "bench_common.h"
#include "../tests/unit/settle_test_scenes.h"
#include "tapmc_contact.h"
#include "tapmc_deposition.h"
#include "tapmc_settle.h"
#include "tapmc_trial_move.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;
using Clock = std::chrono::steady_clock;

using tapmc_bench::cpu_model;
using tapmc_bench::median;
using tapmc_bench::seconds_since;

namespace {

constexpr double kRadius = 1.0;
constexpr double kSide = 32.0 * kRadius;
constexpr double kDmax = 0.2 * kRadius;
constexpr double kTheta0 = 0.78539816339744830962;  // pi/4
constexpr double kTol = 1e-10;                       // paper_params' contact tolerance
constexpr std::uint64_t kSeed = 12345;
constexpr int kN = 4096;




// One trial step across the periodic seam, as the production kernel wraps it.
inline double wrap_step(double x, double length)
{
  if (x < 0.0) {
    x += length;
    if (x >= length) x = 0.0;
  } else if (x >= length) {
    x -= length;
    if (x < 0.0) x = 0.0;
  }
  return x;
}

inline double wrap_into(double x, double length)
{
  x -= length * std::floor(x / length);
  return (x >= 0.0 && x < length) ? x : 0.0;
}

// Trial draws of trials 0, 1, ... in lane-parallel batches; draw_batch is bit-identical to
// draw(), so the moves are those of the production kernel whatever its batch boundaries.
class DrawStream {
 public:
  DrawStream(const TrialMoveSampler &sampler, std::uint64_t stream, std::uint32_t n_pick)
      : sampler_(sampler), rng_(kSeed, stream), n_pick_(n_pick)
  {
  }
  const TrialDraw &at(std::uint64_t t, std::uint64_t end)
  {
    if (t - first_ >= static_cast<std::uint64_t>(count_)) {
      first_ = t;
      count_ = static_cast<int>(std::min<std::uint64_t>(TrialMoveSampler::kBatchMax, end - t));
      sampler_.draw_batch(rng_, t, count_, n_pick_, buf_.data());
    }
    return buf_[t - first_];
  }

 private:
  const TrialMoveSampler &sampler_;
  CounterRandom rng_;
  std::uint32_t n_pick_;
  std::uint64_t first_ = 0;
  int count_ = 0;
  std::array<TrialDraw, TrialMoveSampler::kBatchMax> buf_{};
};

struct RunStats {
  long trials = 0, accepted = 0, builds = 0;
  double seconds = 0.0, mean_list = 0.0;
};

// The paper's initial state (Jullien-Meakin, phi ~ 0.58), then one tap eps = 0.01.
Scene tapped_bed()
{
  DepositionDomain dom;
  dom.xhi = dom.yhi = kSide;
  dom.periodic_x = dom.periodic_y = true;
  Packing pk = deposit_packing(kN, RadiusDistribution::monodisperse(kRadius), dom, 7);
  Scene s;
  s.xyz = pk.xyz;
  s.radius = pk.radius;
  s.box = make_box(kSide, true);
  dilate(s, 0.01);
  return s;
}

SettleParams settle_params(std::uint64_t stream, long trials)
{
  SettleParams p = paper_params(kRadius, kSeed, stream, 1e-300, 1);
  p.check_interval = trials;  // one check at the end: exactly `trials` trials, no eta stop
  return p;
}

RunStats run_settler(Scene &s, std::uint64_t stream, long trials)
{
  Settler settler;
  const Clock::time_point t0 = Clock::now();
  const SettleResult res =
      settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, settle_params(stream, trials));
  RunStats st;
  st.seconds = seconds_since(t0);
  st.trials = res.trials;
  st.accepted = res.accepted;
  return st;
}

// Naive reference: every other sphere, minimum image (the Settler's nearest-image arithmetic:
// bit-identical), early exit on the first overlap.
RunStats run_all_pairs(Scene &s, std::uint64_t stream, long trials)
{
  const int n = s.size();
  const TrialMoveSampler sampler(kDmax, kTheta0);
  DrawStream draws(sampler, stream, static_cast<std::uint32_t>(n));
  const double thr = overlap_threshold_sq(kRadius, kRadius, 1.0 - kTol);
  double *p = s.xyz.data();
  RunStats st;
  const Clock::time_point t0 = Clock::now();
  for (long t = 0; t < trials; ++t) {
    const TrialDraw &d = draws.at(t, trials);
    const int i = static_cast<int>(d.pick);
    const double x = wrap_step(p[3 * i] + d.move.dx, kSide);
    const double y = wrap_step(p[3 * i + 1] + d.move.dy, kSide);
    const double z = p[3 * i + 2] + d.move.dz;
    if (gap_violates(floor_gap(z, kRadius, 0.0), kRadius, kTol)) continue;
    bool overlap = false;
    for (int j = 0; j < n && !overlap; ++j) {
      if (j == i) continue;
      double dx = p[3 * j] - x, dy = p[3 * j + 1] - y;
      dx -= kSide * std::round(dx / kSide);
      dy -= kSide * std::round(dy / kSide);
      overlap = distance_sq(dx, dy, p[3 * j + 2] - z) < thr;
    }
    if (overlap) continue;
    p[3 * i] = x;
    p[3 * i + 1] = y;
    p[3 * i + 2] = z;
    ++st.accepted;
  }
  st.seconds = seconds_since(t0);
  st.trials = trials;
  return st;
}

enum class SkinRule { Lammps, Trial };

// Hard-sphere Monte Carlo on a Verlet neighbour list (see the file comment).
class VerletRun {
 public:
  VerletRun(const Scene &start, double skin, SkinRule rule, bool below_first)
      : n_(start.size()), skin_(skin), rule_(rule), below_first_(below_first)
  {
    if (rule == SkinRule::Trial && skin < kDmax)
      throw std::invalid_argument("VerletRun: skin " + std::to_string(skin) +
                                  " below d_max cannot be exact with the trial rule");
    list_radius_ = 2.0 * kRadius + skin + (rule == SkinRule::Lammps ? kDmax : 0.0);
    list_radius_ *= 1.0 + 1e-12;  // rounding margin: a needed pair is never left out
    x_.resize(n_), y_.resize(n_), z_.resize(n_);
    for (int i = 0; i < n_; ++i) {
      x_[i] = start.xyz[3 * i];
      y_[i] = start.xyz[3 * i + 1];
      z_[i] = start.xyz[3 * i + 2];
    }
  }

  RunStats run(std::uint64_t stream, long trials)
  {
    return rule_ == SkinRule::Lammps ? run_rule<SkinRule::Lammps>(stream, trials)
                                     : run_rule<SkinRule::Trial>(stream, trials);
  }

  // Positions wrapped into the box (for the comparison).
  std::vector<double> positions() const
  {
    std::vector<double> xyz(3 * static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) {
      xyz[3 * i] = wrap_into(x_[i], kSide);
      xyz[3 * i + 1] = wrap_into(y_[i], kSide);
      xyz[3 * i + 2] = z_[i];
    }
    return xyz;
  }

 private:
  template <SkinRule Rule>
  RunStats run_rule(std::uint64_t stream, long trials)
  {
    const TrialMoveSampler sampler(kDmax, kTheta0);
    DrawStream draws(sampler, stream, static_cast<std::uint32_t>(n_));
    const double thr = overlap_threshold_sq(kRadius, kRadius, 1.0 - kTol);
    const double half_skin_sq = 0.25 * skin_ * skin_;
    RunStats st;
    builds_ = 0;
    list_sum_ = 0.0;
    const Clock::time_point t0 = Clock::now();
    build();  // the tap moved every sphere: a list is needed at the start of each redeposition
    for (long t = 0; t < trials; ++t) {
      const TrialDraw &d = draws.at(t, trials);
      const int i = static_cast<int>(d.pick);
      const double z = z_[i] + d.move.dz;
      if (gap_violates(floor_gap(z, kRadius, 0.0), kRadius, kTol)) continue;
      double x = x_[i] + d.move.dx, y = y_[i] + d.move.dy;
      if (Rule == SkinRule::Trial) {
        const double reach = std::sqrt(distance_sq(x - x0_[i], y - y0_[i], z - z0_[i]));
        if (reach + delta_max_ > skin_) {
          build();  // wraps coordinates: recompute the trial position
          x = x_[i] + d.move.dx;
          y = y_[i] + d.move.dy;
        }
      }
      bool overlap = false;
      const int end = first_[i + 1];
      for (int k = first_[i]; k < end; ++k) {
        const int j = nbr_[k];
        const double dx = separation(x_[j], x, shift_x_[k]);
        const double dy = separation(y_[j], y, shift_y_[k]);
        if (distance_sq(dx, dy, z_[j] - z) < thr) {
          overlap = true;
          break;
        }
      }
      if (overlap) continue;
      x_[i] = x;
      y_[i] = y;
      z_[i] = z;
      ++st.accepted;
      const double moved_sq = distance_sq(x - x0_[i], y - y0_[i], z - z0_[i]);
      if (Rule == SkinRule::Lammps) {
        if (moved_sq > half_skin_sq) build();
      } else {
        delta_max_ = std::max(delta_max_, std::sqrt(moved_sq));
      }
    }
    st.seconds = seconds_since(t0);
    st.trials = trials;
    st.builds = builds_;
    st.mean_list = list_sum_ / builds_ / n_;
    return st;
  }

  // O(N) build: wrap (LAMMPS re-wraps at reneighbouring), bin into cells >= list radius,
  // collect every image within the list radius from the 27 surrounding cells.
  void build()
  {
    ++builds_;
    const double rc = list_radius_, rc2 = rc * rc;
    const int nc = static_cast<int>(kSide / rc);
    if (nc < 3) throw std::runtime_error("VerletRun: box too small for the list radius");
    const double inv_w = nc / kSide;
    double zmin = 1e300, zmax = -1e300;
    for (int i = 0; i < n_; ++i) {
      x_[i] = wrap_into(x_[i], kSide);
      y_[i] = wrap_into(y_[i], kSide);
      zmin = std::min(zmin, z_[i]);
      zmax = std::max(zmax, z_[i]);
    }
    const int ncz = static_cast<int>((zmax - zmin) / rc) + 1;
    auto bin = [](double v, double inv, int cells) {
      return std::min(cells - 1, std::max(0, static_cast<int>(v * inv)));
    };
    cell_.resize(n_);
    cell_start_.assign(static_cast<std::size_t>(nc) * nc * ncz + 1, 0);
    for (int i = 0; i < n_; ++i) {
      cell_[i] = (bin(z_[i] - zmin, 1.0 / rc, ncz) * nc + bin(y_[i], inv_w, nc)) * nc +
                 bin(x_[i], inv_w, nc);
      ++cell_start_[cell_[i] + 1];
    }
    for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
    binned_.resize(n_);
    {
      std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
      for (int i = 0; i < n_; ++i) binned_[fill[cell_[i]]++] = i;
    }
    first_.resize(n_ + 1);
    nbr_.clear();
    shift_x_.clear();
    shift_y_.clear();
    for (int i = 0; i < n_; ++i) {
      first_[i] = static_cast<int>(nbr_.size());
      const int c = cell_[i], cx = c % nc, cy = (c / nc) % nc, cz = c / (nc * nc);
      for (int oz = -1; oz <= 1; ++oz) {
        const int czz = cz + oz;
        if (czz < 0 || czz >= ncz) continue;
        for (int oy = -1; oy <= 1; ++oy) {
          int cyy = cy + oy;
          double sy = 0.0;
          if (cyy < 0) {
            cyy += nc;
            sy = -kSide;  // j's image on the low side
          } else if (cyy >= nc) {
            cyy -= nc;
            sy = kSide;
          }
          for (int ox = -1; ox <= 1; ++ox) {
            int cxx = cx + ox;
            double sx = 0.0;
            if (cxx < 0) {
              cxx += nc;
              sx = -kSide;
            } else if (cxx >= nc) {
              cxx -= nc;
              sx = kSide;
            }
            const int cc = (czz * nc + cyy) * nc + cxx;
            for (int q = cell_start_[cc]; q < cell_start_[cc + 1]; ++q) {
              const int j = binned_[q];
              if (j == i) continue;
              const double dx = separation(x_[j], x_[i], sx), dy = separation(y_[j], y_[i], sy);
              if (distance_sq(dx, dy, z_[j] - z_[i]) < rc2) {
                nbr_.push_back(j);
                shift_x_.push_back(sx);
                shift_y_.push_back(sy);
              }
            }
          }
        }
      }
      if (below_first_) sort_below_first(first_[i], static_cast<int>(nbr_.size()));
    }
    first_[n_] = static_cast<int>(nbr_.size());
    list_sum_ += static_cast<double>(nbr_.size());
    x0_ = x_;
    y0_ = y_;
    z0_ = z_;
    delta_max_ = 0.0;
  }

  void sort_below_first(int begin, int end)
  {
    order_.clear();
    for (int k = begin; k < end; ++k) order_.push_back({z_[nbr_[k]], k});
    std::sort(order_.begin(), order_.end());
    entry_j_.clear();
    entry_sx_.clear();
    entry_sy_.clear();
    for (const auto &e : order_) {
      entry_j_.push_back(nbr_[e.second]);
      entry_sx_.push_back(shift_x_[e.second]);
      entry_sy_.push_back(shift_y_[e.second]);
    }
    std::copy(entry_j_.begin(), entry_j_.end(), nbr_.begin() + begin);
    std::copy(entry_sx_.begin(), entry_sx_.end(), shift_x_.begin() + begin);
    std::copy(entry_sy_.begin(), entry_sy_.end(), shift_y_.begin() + begin);
  }

  int n_;
  double skin_, list_radius_ = 0.0, delta_max_ = 0.0, list_sum_ = 0.0;
  SkinRule rule_;
  bool below_first_;
  long builds_ = 0;
  std::vector<double> x_, y_, z_, x0_, y0_, z0_, shift_x_, shift_y_;
  std::vector<int> first_, nbr_, cell_, cell_start_, binned_;
  std::vector<std::pair<double, int>> order_;
  std::vector<int> entry_j_;
  std::vector<double> entry_sx_, entry_sy_;
};

struct Variant {
  SkinRule rule;
  double skin;  // in units of R
  bool below_first;
  std::string name() const
  {
    char buf[96];
    std::snprintf(buf, sizeof buf, "Verlet %s skin %.1fR%s", rule == SkinRule::Lammps ? "lammps" : "trial",
                  skin, below_first ? " below-first" : "");
    return buf;
  }
  double list_radius() const { return 2.0 + skin + (rule == SkinRule::Lammps ? kDmax : 0.0); }
};

// Largest |difference| of two position sets, x and y modulo the period.
double max_difference(const std::vector<double> &a, const std::vector<double> &b)
{
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    double d = std::fabs(a[k] - b[k]);
    if (k % 3 != 2) d = std::min(d, std::fabs(kSide - d));
    worst = std::max(worst, d);
  }
  return worst;
}

std::vector<double> wrapped(const Scene &s)
{
  std::vector<double> xyz = s.xyz;
  for (std::size_t k = 0; k < xyz.size(); ++k)
    if (k % 3 != 2) xyz[k] = wrap_into(xyz[k], kSide);
  return xyz;
}

}  // namespace

int main(int argc, char **argv)
{
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const int repeats = quick ? 3 : 5;
  const long sweeps = quick ? 10 : 50;
  const long trials = sweeps * kN;
  const long check_trials = quick ? 4 * kN : 10 * kN;
  const long naive_trials = quick ? kN : 3 * kN;
  std::printf("bench_neighbor_list: tapmc::Settler (production Verlet list) vs Verlet variants vs all pairs\n");
  std::printf("machine: %s (one core)\n", cpu_model().c_str());
  std::printf("scene: N = %d, L = 32R, PBC + floor, Jullien-Meakin bed after a tap eps = 0.01,\n"
              "       d_max = R/5, theta0 = pi/4; %ld sweeps per timed run, median of %d\n\n",
              kN, sweeps, repeats);

  const Scene after_tap = tapped_bed();
  // Later in the same redeposition (acceptance has dropped): 300 sweeps on.
  Scene mid = after_tap;
  run_settler(mid, 900, 300L * kN);

  std::vector<Variant> variants;
  for (bool below : {false, true}) {
    for (double skin : {0.1, 0.2, 0.4, 0.8}) variants.push_back({SkinRule::Lammps, skin, below});
    for (double skin : {0.2, 0.4, 0.8}) variants.push_back({SkinRule::Trial, skin, below});
  }

  // 1. Same moves, same answer: on the tapped bed (few rebuilds), and on a loose random start
  // (random sequential addition, phi 0.3) where spheres fall far and lists are rebuilt often.
  auto check_same_moves = [&](const Scene &start, const char *label, long n_trials) {
    Scene settler = start, naive = start;
    const RunStats sc = run_settler(settler, 1, n_trials);
    const RunStats sn = run_all_pairs(naive, 1, n_trials);
    const std::vector<double> ref = wrapped(settler);
    std::printf("exactness over %ld trials from %s (tapmc::Settler: %ld accepted):\n", n_trials, label,
                sc.accepted);
    long bitwise = 0;
    for (std::size_t k = 0; k < ref.size(); ++k) bitwise += ref[k] != naive.xyz[k];
    std::printf("  %-36s accepted %7ld  max |dr| %.1e  (%ld coordinates not bit-identical)\n", "all pairs",
                sn.accepted, max_difference(ref, naive.xyz), bitwise);
    bool ok = sn.accepted == sc.accepted && bitwise == 0;
    for (const Variant &v : variants) {
      VerletRun run(start, v.skin * kRadius, v.rule, v.below_first);
      const RunStats sv = run.run(1, n_trials);
      const double diff = max_difference(ref, run.positions());
      std::printf("  %-36s accepted %7ld  max |dr| %.1e  builds %ld\n", v.name().c_str(), sv.accepted, diff,
                  sv.builds);
      ok = ok && sv.accepted == sc.accepted && diff < 1e-9;
    }
    std::printf("  => %s\n\n", ok ? "all methods accept exactly the same moves"
                                  : "MISMATCH: the methods do not accept the same moves");
    return ok;
  };
  if (!check_same_moves(after_tap, "the tapped bed", check_trials)) return 1;
  if (!check_same_moves(random_loose(kN, kSide, kRadius, true, false, 3), "a loose random start",
                        check_trials))
    return 1;

  // 2. Speed, two states of the redeposition.
  for (int which = 0; which < 2; ++which) {
    const Scene &start = which == 0 ? after_tap : mid;
    std::printf("%s:\n", which == 0 ? "first sweeps after the tap" : "300 sweeps after the tap");
    std::vector<double> rates;
    double acceptance = 0.0;
    for (int r = 0; r < repeats; ++r) {
      Scene s = start;
      const RunStats st = run_settler(s, 100 + r, trials);
      rates.push_back(st.trials / st.seconds);
      acceptance = static_cast<double>(st.accepted) / st.trials;
    }
    const double settler_rate = median(rates);
    rates.clear();
    for (int r = 0; r < (quick ? 1 : 3); ++r) {
      Scene s = start;
      const RunStats st = run_all_pairs(s, 100 + r, naive_trials);
      rates.push_back(st.trials / st.seconds);
    }
    const double naive_rate = median(rates);
    std::printf("  acceptance %.4f\n", acceptance);
    std::printf("  %-36s %7s %9s %9s %11s %9s %9s\n", "method", "list r", "builds/sw", "list len",
                "M moves/s", "/all-pairs", "/Settler");
    std::printf("  %-36s %7s %9s %9s %11.3f %9.1f %9.2f\n", "tapmc::Settler (Verlet 0.2R)", "-", "-", "-",
                settler_rate / 1e6, settler_rate / naive_rate, 1.0);
    for (const Variant &v : variants) {
      rates.clear();
      RunStats st;
      for (int r = 0; r < repeats; ++r) {
        VerletRun run(start, v.skin * kRadius, v.rule, v.below_first);
        st = run.run(100 + r, trials);
        rates.push_back(st.trials / st.seconds);
      }
      const double rate = median(rates);
      std::printf("  %-36s %6.1fR %9.2f %9.1f %11.3f %9.1f %9.2f\n", v.name().c_str(), v.list_radius(),
                  static_cast<double>(st.builds) / sweeps, st.mean_list, rate / 1e6, rate / naive_rate,
                  rate / settler_rate);
    }
    std::printf("  %-36s %7s %9s %9d %11.4f %9.1f %9.2f\n\n", "all pairs (reference)", "-", "-", kN - 1,
                naive_rate / 1e6, 1.0, naive_rate / settler_rate);
  }

  // 3. A whole redeposition: the accepted moves are tiny (the tap opens gaps of ~eps * 2R), so
  // how often does a list have to be rebuilt over the ~1000+ sweeps a redeposition takes?
  {
    const long long_sweeps = quick ? 200 : 1000;
    const long long_trials = long_sweeps * kN;
    std::printf("%ld sweeps from the tapped bed (a whole redeposition at eta ~ 1e-6), median of 3:\n",
                long_sweeps);
    std::printf("  %-36s %9s %9s %11s %9s  %s\n", "method", "builds/sw", "list len", "M moves/s", "/Settler",
                "final max |dr| vs Settler");
    std::vector<double> rates, settler_final;
    for (int r = 0; r < 3; ++r) {
      Scene s = after_tap;
      const RunStats st = run_settler(s, 200 + r, long_trials);
      rates.push_back(st.trials / st.seconds);
      if (r == 2) settler_final = wrapped(s);
    }
    const double settler_rate = median(rates);
    std::printf("  %-36s %9s %9s %11.3f %9.2f\n", "tapmc::Settler (Verlet 0.2R)", "-", "-", settler_rate / 1e6, 1.0);
    for (const Variant &v : {Variant{SkinRule::Lammps, 0.1, false}, Variant{SkinRule::Lammps, 0.2, false},
                             Variant{SkinRule::Lammps, 0.4, false}, Variant{SkinRule::Lammps, 0.8, false},
                             Variant{SkinRule::Trial, 0.4, false}}) {
      rates.clear();
      RunStats st;
      std::vector<double> final_xyz;
      for (int r = 0; r < 3; ++r) {
        VerletRun run(after_tap, v.skin * kRadius, v.rule, v.below_first);
        st = run.run(200 + r, long_trials);
        rates.push_back(st.trials / st.seconds);
        if (r == 2) final_xyz = run.positions();  // same stream as the last Settler run
      }
      const double rate = median(rates);
      std::printf("  %-36s %9.3f %9.1f %11.3f %9.2f  %.1e\n", v.name().c_str(),
                  static_cast<double>(st.builds) / long_sweeps, st.mean_list, rate / 1e6, rate / settler_rate,
                  max_difference(settler_final, final_xyz));
    }
  }
  return 0;
}
