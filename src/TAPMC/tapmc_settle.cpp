// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The redeposition kernel: cell-list hard-sphere Monte Carlo with biased downward moves.
#include "tapmc_settle.h"

#include "tapmc_contact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

std::string number(double value)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

[[noreturn]] void bad(const std::string &name, double value, const std::string &range)
{
  throw std::invalid_argument(name + " = " + number(value) + " is outside the allowed range " +
                              range);
}

// Squared distance, written once with explicit fused operations so every caller (vectorised
// kernel loop, scalar violation check) rounds identically.
inline double distance_sq(double dx, double dy, double dz)
{
#ifdef __FMA__
  return std::fma(dz, dz, std::fma(dy, dy, dx * dx));
#else
  return dx * dx + dy * dy + dz * dz;
#endif
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
inline int plane_violation(const Scene &s, double x, double y, double z, double r, double &gap)
{
  gap = floor_gap(z, r, s.floor_z);
  if (gap_violates(gap, r, s.tol)) return -1;
  const double c[2] = {x, y};
  for (int d = 0; d < 2; ++d) {
    gap = std::min(low_wall_gap(c[d], r, s.wall_lo[d]), high_wall_gap(c[d], r, s.wall_hi[d]));
    if (gap_violates(gap, r, s.tol)) return -2 - d;
  }
  return 0;
}

// Cells sized for the largest contact distance plus a rounding margin far below contact_tol,
// covering the periodic period, or the data (and walls / floor) along the other axes.
std::array<GridAxis, 3> make_axes(const Scene &s, const double *xyz, int n, int n_grid_cap)
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
  const double reach = 2.0 * s.r_max * s.one_minus_tol + 1e-12 * (2.0 * s.r_max + scale);

  std::array<GridAxis, 3> axes;
  constexpr int kMaxCellsPerSideAxis = 4096;
  for (int d = 0; d < 2; ++d) {
    if (s.periodic[d])
      axes[d].setup(s.lo[d], s.length[d], reach, true, kMaxCellsPerSideAxis);
    else
      axes[d].setup(mn[d], std::max(mx[d] - mn[d], 0.0), reach, false, kMaxCellsPerSideAxis);
  }
  // Cap the cell count (a floor far below the spheres must not allocate a huge empty grid).
  const int max_z = std::max(1, n_grid_cap / (axes[0].cells * axes[1].cells));
  axes[2].setup(mn[2], std::max(mx[2] - mn[2], 0.0), reach, false, max_z);
  return axes;
}

// Fills `grid` with all spheres (periodic coordinates wrapped; images counted in `image` if
// not null), with enough slots per cell for the fullest cell.
void fill_grid(CellGrid &grid, const std::array<GridAxis, 3> &axes, const Scene &s,
               const double *xyz, int n, int *image)
{
  std::vector<double> wrapped(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) wrapped[3 * i + d] = xyz[3 * i + d];
    for (int d = 0; d < 2; ++d)
      if (s.periodic[d]) {
        int dummy = 0;
        int &im = image ? image[2 * i + d] : dummy;
        wrapped[3 * i + d] = wrap_into_box(xyz[3 * i + d], s.lo[d], s.hi[d], s.length[d], im);
      }
  }
  // Padded cell index as CellGrid::locate computes it, before the storage exists.
  const int px = axes[0].cells + 2, py = axes[1].cells + 2;
  std::vector<int> cell_of(n), fill(static_cast<std::size_t>(px) * py * (axes[2].cells + 2), 0);
  int max_fill = 0;
  for (int i = 0; i < n; ++i) {
    const double *p = &wrapped[3 * i];
    cell_of[i] = ((axes[2].cell_of(p[2]) + 1) * py + axes[1].cell_of(p[1]) + 1) * px +
                 axes[0].cell_of(p[0]) + 1;
    max_fill = std::max(max_fill, ++fill[cell_of[i]]);
  }
  grid.reset(axes, max_fill, !s.mono, n);
  for (int i = 0; i < n; ++i)
    grid.insert(i, cell_of[i], wrapped[3 * i], wrapped[3 * i + 1], wrapped[3 * i + 2],
                radius_of(s, i));
}

// Does a sphere of radius r at (x, y, z) in real cell (ix, iy, iz) overlap any sphere stored
// in the 27 surrounding cells? Layers below first (moves go down, so that is where blockers
// are), early exit after each layer; within a layer no branches. Slots = S (0: runtime).
template <bool Mono, int S>
inline bool stencil_overlap(const CellGrid &grid, int ix, int iy, int iz, double x, double y,
                            double z, double r, double one_minus_tol, double threshold_sq_mono)
{
  const int slots = S ? S : grid.slots();
  const int stride = Mono ? 3 * slots : 4 * slots;
  const GridAxis &ax = grid.axis(0), &ay = grid.axis(1), &az = grid.axis(2);
  const int *nx = ax.neighbour.data() + 3 * ix;
  const int *ny = ay.neighbour.data() + 3 * iy;
  const int *nz = az.neighbour.data() + 3 * iz;
  const double *sx = ax.shift.data() + 3 * ix;
  const double *sy = ay.shift.data() + 3 * iy;
  const int px = grid.padded(0), py = grid.padded(1);
  const double *data = grid.data();
  for (int kz = 0; kz < 3; ++kz) {
    int hit = 0;
    for (int ky = 0; ky < 3; ++ky) {
      const int row = (nz[kz] * py + ny[ky]) * px;
      const double shift_y = sy[ky];
      for (int kx = 0; kx < 3; ++kx) {
        const double *b = data + static_cast<std::size_t>(row + nx[kx]) * stride;
        const double shift_x = sx[kx];
        for (int s = 0; s < slots; ++s) {
          const double dx = separation(b[s], x, shift_x);
          const double dy = separation(b[slots + s], y, shift_y);
          const double dz = b[2 * slots + s] - z;
          const double d2 = distance_sq(dx, dy, dz);
          const double limit =
              Mono ? threshold_sq_mono : overlap_threshold_sq(r, b[3 * slots + s], one_minus_tol);
          hit |= d2 < limit;
        }
      }
    }
    if (hit) return true;
  }
  return false;
}

// The state of one redeposition, kept outside the specialised loop so that a storage growth
// (more slots per cell) can re-dispatch and resume at the same trial.
struct SettleRun {
  Scene scene;
  const TrialMoveSampler *sampler = nullptr;
  CounterRandom rng{0, 0};
  PickOrder order = PickOrder::Random;
  long interval = 0, max_checks = 0;
  double eta = 0.0;
  std::uint64_t trial = 0, next_check = 0;
  long sweep_cursor = 0, accepted = 0, checks = 0;
  double sum_height = 0.0, previous_mean = 0.0;
  bool converged = false, hit_cap = false;
  // Trial draws are made ahead in batches (lane-parallel random numbers); the batch holds
  // trials batch_first .. batch_first + batch_count - 1 and survives a re-dispatch.
  std::array<TrialDraw, TrialMoveSampler::kBatchMax> batch{};
  std::uint64_t batch_first = 0;
  int batch_count = 0;
};

enum class RunStatus { Finished, Regrown };

template <bool Mono, int S>
RunStatus run_trials(SettleRun &run, CellGrid &grid, const std::vector<int> &movable_ids,
                     std::vector<int> &image)
{
  const Scene &sc = run.scene;
  const long m = static_cast<long>(movable_ids.size());
  const std::uint32_t n_pick = run.order == PickOrder::Random ? static_cast<std::uint32_t>(m) : 0u;
  const double threshold_sq_mono = overlap_threshold_sq(sc.r_mono, sc.r_mono, sc.one_minus_tol);
  const int slots = S ? S : grid.slots();
  const GridAxis &ax = grid.axis(0), &ay = grid.axis(1), &az = grid.axis(2);
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
      const int cell = grid.home_cell(i), slot = grid.home_slot(i);
      double *b = grid.block(cell);
      const double ox = b[slot], oy = b[slots + slot], oz = b[2 * slots + slot];
      int *im = image.data() + 2 * i;
      double x = ox + draw.move.dx, y = oy + draw.move.dy;
      const double z = oz + draw.move.dz;
      int wrap_x = 0, wrap_y = 0;
      if (sc.periodic[0]) x = wrap_step(x, sc.lo[0], sc.hi[0], sc.length[0], wrap_x);
      if (sc.periodic[1]) y = wrap_step(y, sc.lo[1], sc.hi[1], sc.length[1], wrap_y);
      double gap;
      if (plane_violation(sc, x, y, z, r, gap)) continue;
      const int ix = ax.cell_of(x), iy = ay.cell_of(y), iz = az.cell_of(z);
      b[slot] = CellGrid::kFar;  // hide the sphere from its own test
      if (stencil_overlap<Mono, S>(grid, ix, iy, iz, x, y, z, r, sc.one_minus_tol,
                                   threshold_sq_mono)) {
        b[slot] = ox;
        continue;
      }
      ++run.accepted;
      run.sum_height += z - oz;  // <Z> kept incrementally (section II)
      im[0] += wrap_x;
      im[1] += wrap_y;
      const int new_cell = grid.cell_index(ix + 1, iy + 1, iz + 1);
      if (new_cell == cell) {
        grid.set_position(i, x, y, z);
      } else if (grid.relocate(i, new_cell, x, y, z, r)) {
        return RunStatus::Regrown;
      }
    }
    // <Z> check every interval (section II): stop on a relative change below eta.
    ++run.checks;
    const double mean = run.sum_height / static_cast<double>(m);
    const double change = std::fabs(mean - run.previous_mean);
    const double relative = run.previous_mean != 0.0 ? change / std::fabs(run.previous_mean)
                                                     : (change == 0.0 ? 0.0 : kInf);
    run.previous_mean = mean;
    if (relative < run.eta) {
      run.converged = true;
      return RunStatus::Finished;
    }
    if (run.checks >= run.max_checks) {
      run.hit_cap = true;
      return RunStatus::Finished;
    }
    run.next_check += static_cast<std::uint64_t>(run.interval);
  }
}

template <bool Mono>
RunStatus dispatch_slots(SettleRun &run, CellGrid &grid, const std::vector<int> &ids,
                         std::vector<int> &image)
{
  switch (grid.slots()) {
    case 4: return run_trials<Mono, 4>(run, grid, ids, image);
    case 8: return run_trials<Mono, 8>(run, grid, ids, image);
    default: return run_trials<Mono, 0>(run, grid, ids, image);
  }
}

}  // namespace

Settler::Settler() = default;
Settler::~Settler() = default;

void Settler::validate(const SettleParams &p)
{
  if (!(p.d_max > 0.0 && std::isfinite(p.d_max))) bad("d_max", p.d_max, "(0, +inf)");
  if (!(p.theta0 > 0.0 && p.theta0 <= 0.5 * kPi)) bad("theta0", p.theta0, "(0, pi/2]");
  if (!(p.eta > 0.0 && std::isfinite(p.eta))) bad("eta", p.eta, "(0, +inf)");
  if (p.check_interval < 0)
    bad("check_interval", static_cast<double>(p.check_interval), "[0, +inf) (0 = one sweep)");
  if (p.max_checks < 1) bad("max_checks", static_cast<double>(p.max_checks), "[1, +inf)");
  if (!(p.contact_tol >= 0.0 && p.contact_tol < 0.1))
    bad("contact_tol", p.contact_tol, "[0, 0.1)");
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
      bad("d_max", params.d_max,
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

  image_.assign(2 * static_cast<std::size_t>(n), 0);
  const int grid_cap = 16 * n + 4096;
  fill_grid(grid_, make_axes(run.scene, xyz, n, grid_cap), run.scene, xyz, n, image_.data());
  const int initial_slots = grid_.slots();

  run.sampler = sampler_.get();
  run.rng = CounterRandom(params.seed, params.stream);
  run.order = params.order;
  run.interval = params.check_interval > 0 ? params.check_interval : m;
  run.max_checks = params.max_checks;
  run.eta = params.eta;
  run.next_check = static_cast<std::uint64_t>(run.interval);
  for (int i : movable_ids_) run.sum_height += grid_.z(i) - box.floor_z;
  run.previous_mean = run.sum_height / static_cast<double>(m);
  result.mean_height_start = run.previous_mean;

  RunStatus status;
  do {
    status = run.scene.mono ? dispatch_slots<true>(run, grid_, movable_ids_, image_)
                            : dispatch_slots<false>(run, grid_, movable_ids_, image_);
  } while (status == RunStatus::Regrown);

  double sum = 0.0;
  for (int i : movable_ids_) {
    xyz[3 * i] = grid_.x(i);
    xyz[3 * i + 1] = grid_.y(i);
    xyz[3 * i + 2] = grid_.z(i);
    sum += xyz[3 * i + 2] - box.floor_z;
    if (image_shift_xy) {
      image_shift_xy[2 * i] += image_[2 * i];
      image_shift_xy[2 * i + 1] += image_[2 * i + 1];
    }
  }
  result.trials = static_cast<long>(run.trial);
  result.accepted = run.accepted;
  result.checks = run.checks;
  result.mean_height = sum / static_cast<double>(m);
  result.hit_cap = run.hit_cap;
  result.slot_growths = 0;
  for (int s = initial_slots; s < grid_.slots(); s *= 2) ++result.slot_growths;
  return result;
}

Violation Settler::find_violation(const double *xyz, const double *radius, int n,
                                  const SettleBox &box, double contact_tol)
{
  if (!(contact_tol >= 0.0 && contact_tol < 0.1)) bad("contact_tol", contact_tol, "[0, 0.1)");
  if (n < 0) bad("n", n, "[0, +inf)");
  Violation v;
  if (n == 0) return v;
  if (!xyz || !radius) throw std::invalid_argument("xyz and radius must not be null when n > 0");
  Scene sc = make_scene(radius, n, box, contact_tol);
  sc.mono = false;  // one generic path: per-pair thresholds from the stored radii
  CellGrid grid;
  fill_grid(grid, make_axes(sc, xyz, n, 16 * n + 4096), sc, xyz, n, nullptr);
  const int slots = grid.slots();
  for (int i = 0; i < n; ++i) {
    const double x = grid.x(i), y = grid.y(i), z = grid.z(i), r = radius[i];
    double gap;
    if (const int code = plane_violation(sc, x, y, z, r, gap)) {
      v.i = i;
      v.j = code;
      v.gap = gap;
      return v;
    }
    int ix, iy, iz;
    grid.real_coords(grid.home_cell(i), ix, iy, iz);
    const GridAxis &ax = grid.axis(0), &ay = grid.axis(1), &az = grid.axis(2);
    for (int kz = 0; kz < 3; ++kz)
      for (int ky = 0; ky < 3; ++ky)
        for (int kx = 0; kx < 3; ++kx) {
          const int cell = grid.cell_index(ax.neighbour[3 * ix + kx], ay.neighbour[3 * iy + ky],
                                           az.neighbour[3 * iz + kz]);
          const double *b = grid.block(cell);
          for (int s = 0; s < grid.count(cell); ++s) {
            const int j = grid.owner(cell, s);
            if (j == i) continue;
            const double dx = separation(b[s], x, ax.shift[3 * ix + kx]);
            const double dy = separation(b[slots + s], y, ay.shift[3 * iy + ky]);
            const double dz = b[2 * slots + s] - z;
            const double d2 = distance_sq(dx, dy, dz);
            if (d2 < overlap_threshold_sq(r, radius[j], sc.one_minus_tol)) {
              v.i = i;
              v.j = j;
              v.gap = std::sqrt(d2) - (r + radius[j]);
              return v;
            }
          }
        }
  }
  return v;
}

}  // namespace tapmc
