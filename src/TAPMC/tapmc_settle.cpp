// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The redeposition kernel: hard-sphere Monte Carlo with biased downward moves (paper, section
// II) on a kernel-owned Verlet neighbour list.
//
// The list (why a kernel-owned Verlet list, and its skin: bench/bench_neighbor_list.cpp and
// bench/README.md): each movable sphere i lists every sphere j whose nearest periodic image lies
// within (R_i + R_j) + d_max + skin at the build. A trial puts i at most d_max from its current
// position, and no sphere has moved more than skin/2 since the build (an accepted move that
// takes a sphere further triggers an O(N) rebuild by binning at once), so by the triangle
// inequality every sphere the trial can overlap is listed: the list never misses an overlap and
// the accepted moves do not depend on the skin. Positions stay wrapped into the box, and the
// overlap test takes the nearest image of each listed sphere (the separation() arithmetic of
// tapmc_contact.h), so a sphere crossing a periodic side needs no rebuild. The skin starts at
// 0.2 R_max each call and adapts (tapmc_defaults.h): doubled when rebuilds come less than a
// sweep apart (spheres falling freely from a loose start), halved back after 64 calm sweeps;
// being exact, the list gives the same moves whatever the skin. The list build and
// find_violation search through one cell grid (tapmc_cell_grid.h).
#include "tapmc_settle.h"

#include "tapmc_cell_grid.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
#include "tapmc_stop_rule.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace tapmc {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
[[noreturn]] void bad(const std::string &name, double value, const std::string &range)
{
  throw std::invalid_argument(name + " = " + number(value) + " is outside the allowed range " +
                              range);
}

void check_contact_tol(double contact_tol)
{
  if (!(contact_tol >= 0.0 && contact_tol < defaults::kMaxContactTolerance))
    bad("contact_tol", contact_tol, "[0, " + number(defaults::kMaxContactTolerance) + ")");
}

void check_check_interval(long check_interval)
{
  if (check_interval < 0)
    bad("check", static_cast<double>(check_interval), "[0, +inf) (0 = one sweep)");
}

// Wraps a coordinate into [lo, hi) along a periodic axis, counting periods in `image`
// (x_unwrapped = x + image * L). Works for any distance; lands on lo if rounding at the seam
// would give hi.
inline double wrap_into_box(double x, double lo, double hi, double length, int &image)
{
  if (x >= lo && x < hi) return x;
  const double k = std::floor((x - lo) / length);
  x -= k * length;
  image += static_cast<int>(k);
  if (x < lo) {
    x += length;
    image -= 1;
  } else if (x >= hi) {
    x -= length;
    image += 1;
  }
  if (!(x >= lo && x < hi)) x = lo;  // the seam: lo and hi are the same point modulo L
  return x;
}

// The same for one trial step (|step| < L): at most one period.
inline double wrap_step(double x, double lo, double hi, double length, int &image)
{
  if (x < lo) {
    x += length;
    image -= 1;
    if (x >= hi) x = lo;
  } else if (x >= hi) {
    x -= length;
    image += 1;
    if (x < lo) x = lo;
  }
  return x;
}

// Everything about the scene that stays fixed during one call.
struct Scene {
  const double *radius = nullptr;
  bool mono = true;
  double r_mono = 0.0, r_max = 0.0, r_min = 0.0;
  double tol = 0.0, one_minus_tol = 1.0;
  bool periodic[2] = {false, false};
  double lo[2] = {0, 0}, hi[2] = {0, 0}, length[2] = {0, 0};
  // Side planes; -inf / +inf where there is none, so the plane tests never fire.
  double wall_lo[2] = {-kInf, -kInf}, wall_hi[2] = {kInf, kInf};
  double floor_z = 0.0;
};

Scene make_scene(const double *radius, int n, const SettleBox &box, double contact_tol)
{
  Scene s;
  s.radius = radius;
  s.tol = contact_tol;
  s.one_minus_tol = 1.0 - contact_tol;
  s.floor_z = box.floor_z;
  if (!std::isfinite(box.floor_z)) bad("floor_z", box.floor_z, "(finite)");
  if (n > 0) {
    s.r_min = s.r_max = radius[0];
    for (int i = 0; i < n; ++i) {
      const double r = radius[i];
      if (!(r > 0.0 && std::isfinite(r)))
        bad("radius[" + std::to_string(i) + "]", r, "(0, +inf)");
      s.r_min = std::min(s.r_min, r);
      s.r_max = std::max(s.r_max, r);
    }
  }
  s.mono = (s.r_min == s.r_max);
  s.r_mono = s.r_max;
  const char *axis_name[2] = {"x", "y"};
  for (int d = 0; d < 2; ++d) {
    s.periodic[d] = box.periodic[d];
    s.lo[d] = box.lo[d];
    s.hi[d] = box.hi[d];
    if (box.periodic[d]) {
      if (!(std::isfinite(box.lo[d]) && std::isfinite(box.hi[d]) && box.hi[d] > box.lo[d]))
        throw std::invalid_argument(std::string("box ") + axis_name[d] + " bounds [" +
                                    number(box.lo[d]) + ", " + number(box.hi[d]) +
                                    ") of a periodic axis must be finite with lo < hi");
      s.length[d] = box.hi[d] - box.lo[d];
      if (s.length[d] < 2.0 * s.r_max)
        bad(std::string("periodic box length ") + axis_name[d], s.length[d],
            "[2 R_max, +inf) = [" + number(2.0 * s.r_max) + ", +inf)");
      if (box.wall_lo[d] || box.wall_hi[d])
        throw std::invalid_argument(std::string("wall_lo/wall_hi[") + axis_name[d] +
                                    "] set on a periodic axis: walls need a non-periodic axis");
    } else {
      if (box.wall_lo[d]) {
        if (!std::isfinite(box.wall_lo_pos[d]))
          bad(std::string("wall_lo_pos[") + axis_name[d] + "]", box.wall_lo_pos[d], "(finite)");
        s.wall_lo[d] = box.wall_lo_pos[d];
      }
      if (box.wall_hi[d]) {
        if (!std::isfinite(box.wall_hi_pos[d]))
          bad(std::string("wall_hi_pos[") + axis_name[d] + "]", box.wall_hi_pos[d], "(finite)");
        s.wall_hi[d] = box.wall_hi_pos[d];
      }
      if (box.wall_lo[d] && box.wall_hi[d] && !(box.wall_lo_pos[d] < box.wall_hi_pos[d]))
        bad(std::string("wall_hi_pos[") + axis_name[d] + "]", box.wall_hi_pos[d],
            "(wall_lo_pos, +inf) = (" + number(box.wall_lo_pos[d]) + ", +inf)");
    }
  }
  return s;
}

inline double radius_of(const Scene &s, int i) { return s.mono ? s.r_mono : s.radius[i]; }

// The plane constraints (floor, side walls) of a sphere of radius r at (x, y, z): 0 if none is
// violated, else the code of the first (-1 floor, -2 x wall, -3 y wall) and its gap.
// Floor, then side walls; a periodic axis has no walls, and the hot loop (which knows its axes
// at compile time) skips their tests. Returns 0, or -1 floor / -2 x wall / -3 y wall.
template <bool PeriodicX, bool PeriodicY>
inline int plane_violation(const Scene &s, double x, double y, double z, double r, double &gap)
{
  gap = floor_gap(z, r, s.floor_z);
  if (gap_violates(gap, r, s.tol)) return -1;
  if (!PeriodicX) {
    gap = std::min(low_wall_gap(x, r, s.wall_lo[0]), high_wall_gap(x, r, s.wall_hi[0]));
    if (gap_violates(gap, r, s.tol)) return -2;
  }
  if (!PeriodicY) {
    gap = std::min(low_wall_gap(y, r, s.wall_lo[1]), high_wall_gap(y, r, s.wall_hi[1]));
    if (gap_violates(gap, r, s.tol)) return -3;
  }
  return 0;
}

// Cells sized for the largest contact distance plus a rounding margin far below contact_tol,
// covering the periodic period, or the data (and walls / floor) along the other axes.
// extra_reach widens the cells beyond the contact distance (the Verlet list's d_max + skin).
std::array<GridAxis, 3> make_axes(const Scene &s, const double *xyz, int n,
                                  double extra_reach = 0.0)
{
  double mn[3] = {kInf, kInf, kInf}, mx[3] = {-kInf, -kInf, -kInf};
  double scale = 0.0;
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const double v = xyz[3 * i + d];
      mn[d] = std::min(mn[d], v);
      mx[d] = std::max(mx[d], v);
      scale = std::max(scale, std::fabs(v));
    }
  for (int d = 0; d < 2; ++d) {
    if (std::isfinite(s.wall_lo[d])) mn[d] = std::min(mn[d], s.wall_lo[d]);
    if (std::isfinite(s.wall_hi[d])) mx[d] = std::max(mx[d], s.wall_hi[d]);
    scale = std::max({scale, std::fabs(s.lo[d]), std::fabs(s.hi[d])});
  }
  mn[2] = std::min(mn[2], s.floor_z);  // movable spheres only go down, at most to the floor
  scale = std::max(scale, std::fabs(s.floor_z));
  const double margin = defaults::kGridRoundingMargin * (2.0 * s.r_max + scale);
  const double reach = 2.0 * s.r_max * s.one_minus_tol + extra_reach + margin;

  std::array<GridAxis, 3> axes;
  const int max_side = defaults::kGridMaxCellsPerSideAxis;
  for (int d = 0; d < 2; ++d) {
    if (s.periodic[d])
      axes[d].setup(s.lo[d], s.length[d], reach, true, max_side);
    else
      axes[d].setup(mn[d], std::max(mx[d] - mn[d], 0.0), reach, false, max_side);
  }
  // Cap the cell count (a floor far below the spheres must not allocate a huge empty grid).
  const int max_cells = defaults::kGridCellsPerSphere * n + defaults::kGridMinCells;
  const int max_z = std::max(1, max_cells / (axes[0].cells * axes[1].cells));
  axes[2].setup(mn[2], std::max(mx[2] - mn[2], 0.0), reach, false, max_z);
  return axes;
}

// Separation of j from i along a periodic axis, nearest image: the shift (0 or +-L) is chosen
// from the raw difference and added last, exactly as separation() with a cell's image shift.
inline double nearest_separation(double x_j, double x_i, double length, double half_length)
{
  const double raw = x_j - x_i;
  const double shift = raw > half_length ? -length : (raw < -half_length ? length : 0.0);
  return separation(x_j, x_i, shift);
}

template <bool Periodic>
inline double axis_separation(double x_j, double x_i, double length, double half_length)
{
  return Periodic ? nearest_separation(x_j, x_i, length, half_length) : x_j - x_i;
}

}  // namespace

// The Verlet list of the movable spheres, CSR over the movable index k (movable_ids[k]).
struct detail::NeighbourLists {
  std::vector<int> first, neighbour;  // neighbours of k: neighbour[first[k] .. first[k+1])
  std::vector<double> reference;      // position of k at the build (3 per k), moved with its wraps
  CellGrid grid;          // binning of the build, reused
  std::vector<int> seen;  // repeat filter of the build (periodic axes of fewer than 3 cells)
  double skin = 0.0, half_skin_sq = 0.0;
  double list_extra = 0.0;  // d_max + skin, added to R_i + R_j
  double d_max = 0.0, base_skin = 0.0, max_skin = 0.0;
  std::uint64_t built_at_trial = 0;
  long builds = 0;

  // Takes effect at the next build (the trigger and the list radius must use the same skin).
  void set_skin(double new_skin)
  {
    skin = new_skin;
    half_skin_sq = 0.25 * skin * skin;
    list_extra = d_max + skin;
  }
};

namespace {

using detail::NeighbourLists;

// Does a sphere of radius r at (x, y, z) overlap one of the listed spheres (nearest image)?
// Flat loop, early exit on the first overlap.
template <bool Mono, bool PeriodicX, bool PeriodicY>
inline bool list_overlap(const int *begin, const int *end, const double *pos, const Scene &sc,
                         double x, double y, double z, double r, double threshold_sq_mono,
                         double half_x, double half_y)
{
  for (const int *p = begin; p != end; ++p) {
    const int j = *p;
    const double *q = pos + 3 * j;
    const double dx = axis_separation<PeriodicX>(q[0], x, sc.length[0], half_x);
    const double dy = axis_separation<PeriodicY>(q[1], y, sc.length[1], half_y);
    const double dz = q[2] - z;
    const double limit =
        Mono ? threshold_sq_mono : overlap_threshold_sq(r, sc.radius[j], sc.one_minus_tol);
    if (distance_sq(dx, dy, dz) < limit) return true;
  }
  return false;
}

// The state of one redeposition.
struct SettleRun {
  Scene scene;
  const TrialMoveSampler *sampler = nullptr;
  CounterRandom rng{0, 0};
  PickOrder order = PickOrder::Random;
  long interval = 0;
  std::unique_ptr<ConvergenceCheck> stop;
  long accepted_at_check = 0;  // run.accepted at the previous check
  std::uint64_t trial = 0, next_check = 0;
  long sweep_cursor = 0, accepted = 0;
  double sum_height = 0.0;
  bool converged = false, hit_cap = false;
  // Trial draws are made ahead in batches (lane-parallel random numbers); the batch holds
  // trials batch_first .. batch_first + batch_count - 1.
  std::array<TrialDraw, TrialMoveSampler::kBatchMax> batch{};
  std::uint64_t batch_first = 0;
  int batch_count = 0;
};

// O(N) build: bin all spheres into cells at least one list radius wide, then keep for each
// movable sphere the others whose nearest image is within (R_i + R_j) + d_max + skin.
void build_lists(NeighbourLists &lists, const Scene &s, const double *pos, int n,
                 const std::vector<int> &ids)
{
  std::vector<int> &seen = lists.seen, &first = lists.first, &neighbour = lists.neighbour;
  std::vector<double> &reference = lists.reference;
  ++lists.builds;
  double scale = std::max(std::fabs(s.floor_z), 2.0 * s.r_max);
  for (int i = 0; i < 3 * n; ++i) scale = std::max(scale, std::fabs(pos[i]));
  for (int d = 0; d < 2; ++d) scale = std::max({scale, std::fabs(s.lo[d]), std::fabs(s.hi[d])});
  // Rounding margin of the list radius (positions, steps and wraps round at ~1e-16 * scale).
  const double margin = defaults::kGridRoundingMargin * (2.0 * s.r_max + scale);
  const double extra = lists.list_extra + margin;
  CellGrid &grid = lists.grid;
  grid.build(make_axes(s, pos, n, 2.0 * s.r_max * s.tol + extra + margin), pos,
             s.radius, n);

  const long m = static_cast<long>(ids.size());
  first.resize(m + 1);
  reference.resize(3 * static_cast<std::size_t>(m));
  const bool repeats = grid.visits_repeat();  // only then are repeats filtered
  if (repeats) seen.assign(n, -1);
  const double half_x = 0.5 * s.length[0], half_y = 0.5 * s.length[1];
  std::size_t count = 0;
  for (long k = 0; k < m; ++k) {
    const int i = ids[k];
    const double *pi = pos + 3 * i;
    const double ri = radius_of(s, i);
    first[k] = static_cast<int>(count);
    for (int d = 0; d < 3; ++d) reference[3 * k + d] = pi[d];
    // neighbour only grows (its size is a capacity; first[] marks the entries in use)
    if (neighbour.size() < count + grid.max_visited())
      neighbour.resize(2 * (count + grid.max_visited()) + 64);
    int *out = neighbour.data();
    grid.visit_neighbours(pi[0], pi[1], pi[2], [&](int j, const double *pj, double, double) {
      const double dx =
          s.periodic[0] ? nearest_separation(pj[0], pi[0], s.length[0], half_x) : pj[0] - pi[0];
      const double dy =
          s.periodic[1] ? nearest_separation(pj[1], pi[1], s.length[1], half_y) : pj[1] - pi[1];
      const double list_radius = (ri + pj[3]) + extra;
      bool keep = (distance_sq(dx, dy, pj[2] - pi[2]) < list_radius * list_radius) & (j != i);
      if (repeats) {
        keep = keep && seen[j] != k;
        if (keep) seen[j] = static_cast<int>(k);
      }
      out[count] = j;  // branch-free append: kept entries advance the end
      count += keep;
      return false;
    });
  }
  first[m] = static_cast<int>(count);
}

template <bool Mono, bool PeriodicX, bool PeriodicY>
void run_trials(SettleRun &run, double *pos, const std::vector<int> &movable_ids,
                std::vector<int> &image, NeighbourLists &lists)
{
  const Scene &sc = run.scene;
  const long m = static_cast<long>(movable_ids.size());
  const std::uint32_t n_pick = run.order == PickOrder::Random ? static_cast<std::uint32_t>(m) : 0u;
  const double threshold_sq_mono = overlap_threshold_sq(sc.r_mono, sc.r_mono, sc.one_minus_tol);
  const double half_x = 0.5 * sc.length[0], half_y = 0.5 * sc.length[1];
  const int n = static_cast<int>(image.size() / 2);
  for (;;) {
    while (run.trial < run.next_check) {
      const std::uint64_t t = run.trial++;
      if (t - run.batch_first >= static_cast<std::uint64_t>(run.batch_count)) {
        run.batch_first = t;
        run.batch_count = static_cast<int>(std::min<std::uint64_t>(
            TrialMoveSampler::kBatchMax, run.next_check - t));
        run.sampler->draw_batch(run.rng, t, run.batch_count, n_pick, run.batch.data());
      }
      const TrialDraw &draw = run.batch[t - run.batch_first];
      long k;
      if (n_pick) {
        k = draw.pick;
      } else {
        k = run.sweep_cursor;
        if (++run.sweep_cursor == m) run.sweep_cursor = 0;
      }
      const int i = movable_ids[k];
      const double r = Mono ? sc.r_mono : sc.radius[i];
      double *p = pos + 3 * i;
      const double ox = p[0], oy = p[1], oz = p[2];
      double x = ox + draw.move.dx, y = oy + draw.move.dy;
      const double z = oz + draw.move.dz;
      int wrap_x = 0, wrap_y = 0;
      if (PeriodicX) x = wrap_step(x, sc.lo[0], sc.hi[0], sc.length[0], wrap_x);
      if (PeriodicY) y = wrap_step(y, sc.lo[1], sc.hi[1], sc.length[1], wrap_y);
      double gap;
      if (plane_violation<PeriodicX, PeriodicY>(sc, x, y, z, r, gap)) continue;
      const int *nb = lists.neighbour.data();
      if (list_overlap<Mono, PeriodicX, PeriodicY>(nb + lists.first[k], nb + lists.first[k + 1],
                                                   pos, sc, x, y, z, r, threshold_sq_mono,
                                                   half_x, half_y))
        continue;
      ++run.accepted;
      run.sum_height += z - oz;  // <Z> kept incrementally (section II)
      p[0] = x;
      p[1] = y;
      p[2] = z;
      double *ref = lists.reference.data() + 3 * k;
      if (PeriodicX && wrap_x) {  // keep the reference in the sphere's new frame
        image[2 * i] += wrap_x;
        ref[0] += wrap_x * sc.length[0];
      }
      if (PeriodicY && wrap_y) {
        image[2 * i + 1] += wrap_y;
        ref[1] += wrap_y * sc.length[1];
      }
      if (distance_sq(x - ref[0], y - ref[1], z - ref[2]) > lists.half_skin_sq) {
        // Rebuilds in quick succession (free fall): a wider skin, fewer O(N) builds.
        if (static_cast<double>(run.trial - lists.built_at_trial) <
            defaults::kVerletGrowBelowSweeps * static_cast<double>(m))
          lists.set_skin(std::min(2.0 * lists.skin, lists.max_skin));
        build_lists(lists, sc, pos, n, movable_ids);
        lists.built_at_trial = run.trial;
      }
    }
    // <Z> check every interval (section II), by the rule of tapmc_stop_rule.h.
    const ConvergenceCheck::Verdict verdict = run.stop->after_check(
        run.sum_height / static_cast<double>(m), run.accepted - run.accepted_at_check,
        run.interval);
    run.accepted_at_check = run.accepted;
    if (verdict == ConvergenceCheck::Verdict::Converged) {
      run.converged = true;
      return;
    }
    if (verdict == ConvergenceCheck::Verdict::HitCap) {
      run.hit_cap = true;
      return;
    }
    run.next_check += static_cast<std::uint64_t>(run.interval);
    // Back towards the default skin (shorter lists) once the packing has calmed down.
    if (lists.skin > lists.base_skin &&
        static_cast<double>(run.trial - lists.built_at_trial) >=
            defaults::kVerletShrinkAfterSweeps * static_cast<double>(m)) {
      lists.set_skin(std::max(0.5 * lists.skin, lists.base_skin));
      build_lists(lists, sc, pos, n, movable_ids);
      lists.built_at_trial = run.trial;
    }
  }
}

// Mono / poly and periodic / walls chosen once per call.
template <bool Mono>
void dispatch_axes(SettleRun &run, double *pos, const std::vector<int> &ids,
                   std::vector<int> &image, NeighbourLists &lists)
{
  const bool px = run.scene.periodic[0], py = run.scene.periodic[1];
  if (px && py) run_trials<Mono, true, true>(run, pos, ids, image, lists);
  else if (px) run_trials<Mono, true, false>(run, pos, ids, image, lists);
  else if (py) run_trials<Mono, false, true>(run, pos, ids, image, lists);
  else run_trials<Mono, false, false>(run, pos, ids, image, lists);
}

}  // namespace

Settler::Settler()
    : lists_(std::make_unique<detail::NeighbourLists>()),
      skin_over_max_radius_(defaults::kVerletSkinOverRadius)
{
}

void Settler::set_verlet_skin(double skin_over_max_radius)
{
  if (!(skin_over_max_radius > 0.0 && std::isfinite(skin_over_max_radius)))
    bad("verlet skin (units of R_max)", skin_over_max_radius, "(0, +inf)");
  skin_over_max_radius_ = skin_over_max_radius;
}

Settler::~Settler() = default;

void Settler::validate(const SettleParams &p)
{
  if (!(p.d_max > 0.0 && std::isfinite(p.d_max))) bad("dmax", p.d_max, "(0, +inf)");
  if (!(p.theta0 > 0.0 && p.theta0 <= 0.5 * kPi)) bad("theta0", p.theta0, "(0, pi/2]");
  if (!(p.eta > 0.0 && p.eta < 1.0)) bad("eta", p.eta, "(0, 1) (relative change of <Z>)");
  if (!(p.drift_window >= 2 && p.drift_window <= defaults::kSettleDriftWindowMax))
    bad("window", static_cast<double>(p.drift_window),
        "[2, " + std::to_string(defaults::kSettleDriftWindowMax) +
            "] (checks averaged by 'stop drift')");
  check_check_interval(p.check_interval);
  if (p.max_checks < 1) bad("max_checks", static_cast<double>(p.max_checks), "[1, +inf)");
  check_contact_tol(p.contact_tol);
}

long Settler::trials_per_check(long check_interval, long movable)
{
  return check_interval > 0 ? check_interval : movable;
}

ConvergenceCheck Settler::make_convergence_check(const SettleParams &params, long movable,
                                                 double mean_height_start)
{
  if (movable < 1) bad("movable", static_cast<double>(movable), "[1, +inf)");
  const long interval = trials_per_check(params.check_interval, movable);
  return ConvergenceCheck(params.stop, params.eta, params.max_checks, mean_height_start,
                          static_cast<double>(interval) / static_cast<double>(movable),
                          params.drift_window, defaults::kSettleDriftConfidence);
}

long Settler::max_checks_for_sweeps(long max_sweeps, long check_interval, long movable)
{
  check_check_interval(check_interval);
  if (max_sweeps < 1) bad("maxsweeps", static_cast<double>(max_sweeps), "[1, +inf)");
  const long interval = trials_per_check(check_interval, movable);
  return std::max(1L, (max_sweeps * movable + interval - 1) / interval);
}

SettleResult Settler::settle(double *xyz, const double *radius, const unsigned char *movable,
                             int n, const SettleBox &box, const SettleParams &params)
{
  return settle(xyz, radius, movable, n, box, params, nullptr);
}

SettleResult Settler::settle(double *xyz, const double *radius, const unsigned char *movable,
                             int n, const SettleBox &box, const SettleParams &params,
                             int *image_shift_xy)
{
  validate(params);
  if (n < 0) bad("n", n, "[0, +inf)");
  if (n > 0 && (!xyz || !radius))
    throw std::invalid_argument("xyz and radius must not be null when n > 0");
  SettleRun run;
  run.scene = make_scene(radius, n, box, params.contact_tol);
  for (int d = 0; d < 2; ++d)
    if (run.scene.periodic[d] && !(params.d_max < run.scene.length[d]))
      bad("dmax", params.d_max,
          "(0, periodic length) = (0, " + number(run.scene.length[d]) + ")");

  movable_ids_.clear();
  for (int i = 0; i < n; ++i)
    if (!movable || movable[i]) movable_ids_.push_back(i);
  SettleResult result;
  const long m = static_cast<long>(movable_ids_.size());
  result.movable = m;
  if (m == 0) return result;
  if (static_cast<std::uint64_t>(m) >= (std::uint64_t{1} << 32))
    bad("number of movable spheres", static_cast<double>(m), "[0, 2^32)");

  if (!sampler_ || sampler_->d_max() != params.d_max ||
      sampler_->theta_sampler().theta0() != params.theta0)
    sampler_ = std::make_unique<TrialMoveSampler>(params.d_max, params.theta0);

  // Working positions, periodic axes wrapped into the box (wraps counted as images).
  image_.assign(2 * static_cast<std::size_t>(n), 0);
  position_.assign(xyz, xyz + 3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      if (run.scene.periodic[d])
        position_[3 * i + d] = wrap_into_box(xyz[3 * i + d], run.scene.lo[d], run.scene.hi[d],
                                             run.scene.length[d], image_[2 * i + d]);
  NeighbourLists &lists = *lists_;
  lists.d_max = params.d_max;
  lists.base_skin = skin_over_max_radius_ * run.scene.r_max;
  lists.max_skin = std::max(lists.base_skin, defaults::kVerletSkinMaxOverRadius * run.scene.r_max);
  lists.set_skin(lists.base_skin);
  lists.builds = 0;
  lists.built_at_trial = 0;
  build_lists(lists, run.scene, position_.data(), n, movable_ids_);

  run.sampler = sampler_.get();
  run.rng = CounterRandom(params.seed, params.stream);
  run.order = params.order;
  run.interval = trials_per_check(params.check_interval, m);
  run.next_check = static_cast<std::uint64_t>(run.interval);
  for (int i : movable_ids_) run.sum_height += position_[3 * i + 2] - box.floor_z;
  result.mean_height_start = run.sum_height / static_cast<double>(m);
  run.stop = std::make_unique<ConvergenceCheck>(
      make_convergence_check(params, m, result.mean_height_start));

  if (run.scene.mono)
    dispatch_axes<true>(run, position_.data(), movable_ids_, image_, lists);
  else
    dispatch_axes<false>(run, position_.data(), movable_ids_, image_, lists);

  double sum = 0.0;
  for (int i : movable_ids_) {
    xyz[3 * i] = position_[3 * i];
    xyz[3 * i + 1] = position_[3 * i + 1];
    xyz[3 * i + 2] = position_[3 * i + 2];
    sum += xyz[3 * i + 2] - box.floor_z;
    if (image_shift_xy) {
      image_shift_xy[2 * i] += image_[2 * i];
      image_shift_xy[2 * i + 1] += image_[2 * i + 1];
    }
  }
  result.trials = static_cast<long>(run.trial);
  result.accepted = run.accepted;
  result.checks = run.stop->checks();
  result.mean_height = sum / static_cast<double>(m);
  result.hit_cap = run.hit_cap;
  result.list_builds = lists.builds;
  return result;
}

Violation Settler::find_violation(const double *xyz, const double *radius, int n,
                                  const SettleBox &box, double contact_tol)
{
  check_contact_tol(contact_tol);
  if (n < 0) bad("n", n, "[0, +inf)");
  Violation v;
  if (n == 0) return v;
  if (!xyz || !radius) throw std::invalid_argument("xyz and radius must not be null when n > 0");
  Scene sc = make_scene(radius, n, box, contact_tol);
  // Positions with periodic axes wrapped into the box.
  std::vector<double> wrapped(xyz, xyz + 3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      if (sc.periodic[d]) {
        int image = 0;
        wrapped[3 * i + d] = wrap_into_box(xyz[3 * i + d], sc.lo[d], sc.hi[d], sc.length[d], image);
      }
  CellGrid grid;
  grid.build(make_axes(sc, xyz, n), wrapped.data(), radius, n);
  for (int i = 0; i < n; ++i) {
    const double x = wrapped[3 * i], y = wrapped[3 * i + 1], z = wrapped[3 * i + 2];
    const double r = radius[i];
    double gap;
    if (const int code = plane_violation<false, false>(sc, x, y, z, r, gap)) {
      v.i = i;
      v.j = code;
      v.gap = gap;
      return v;
    }
    // The image shift of each cell (not the nearest image): with fewer than 3 cells along a
    // periodic axis every image in reach is tested.
    const bool found = grid.visit_neighbours(x, y, z, [&](int j, const double *pj, double shift_x,
                                                          double shift_y) {
      if (j == i) return false;
      const double d2 =
          distance_sq(separation(pj[0], x, shift_x), separation(pj[1], y, shift_y), pj[2] - z);
      if (!(d2 < overlap_threshold_sq(r, pj[3], sc.one_minus_tol))) return false;
      v.j = j;
      v.gap = std::sqrt(d2) - (r + pj[3]);
      return true;
    });
    if (found) {
      v.i = i;
      return v;
    }
  }
  return v;
}

}  // namespace tapmc
