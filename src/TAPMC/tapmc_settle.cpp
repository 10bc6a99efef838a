// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The redeposition kernel: hard-sphere Monte Carlo with biased downward moves (paper, section
// II) until <Z> converges. The trials run on the trial-move engine (tapmc_sphere_mover.h: exact
// neighbour lists kept up to date locally), in blocks of one check interval; between blocks the
// stopping rule of tapmc_stop_rule.h reads <Z>, which the engine keeps as a running sum of the
// accepted z changes in trial order. The violation check searches through a cell grid
// (tapmc_cell_grid.h).
#include "tapmc_settle.h"

#include "tapmc_cell_grid.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_settle_geometry.h"
#include "tapmc_sphere_mover.h"
#include "tapmc_stop_rule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace tapmc {

using namespace settle_geometry;

namespace {

// Scratch of find_violation, reused between calls on one thread (no allocation once warm).
struct ViolationScratch {
  std::vector<double> wrapped;
  CellGrid grid;
};

}  // namespace

Settler::Settler()
    : mover_(std::make_unique<SphereMover>()),
      skin_over_max_radius_(defaults::kListSkinOverRadius)
{
}

void Settler::set_verlet_skin(double skin_over_max_radius)
{
  mover_->set_skin(skin_over_max_radius);
  skin_over_max_radius_ = skin_over_max_radius;
}

Settler::~Settler() = default;

void Settler::validate(const SettleParams &p)
{
  if (!(p.d_max > 0.0 && std::isfinite(p.d_max)))
    throw_outside_range("dmax", p.d_max, "(0, +inf)");
  if (!(p.theta0 > 0.0 && p.theta0 <= defaults::kThetaWidthMax))
    throw_outside_range("theta0", p.theta0, defaults::kThetaWidthRange);
  if (!(p.eta > 0.0 && p.eta < 1.0))
    throw_outside_range("eta", p.eta, "(0, 1) (relative change of <Z>)");
  if (!(p.drift_window >= 2 && p.drift_window <= defaults::kSettleDriftWindowMax))
    throw_outside_range("window", p.drift_window,
                        "[2, " + std::to_string(defaults::kSettleDriftWindowMax) +
                            "] (checks averaged by 'stop drift')");
  check_check_interval(p.check_interval);
  if (p.max_checks < 1) throw_outside_range("max_checks", p.max_checks, "[1, +inf)");
  check_contact_tol(p.contact_tol);
}

long Settler::trials_per_check(long check_interval, long movable)
{
  return check_interval > 0 ? check_interval : movable;
}

ConvergenceCheck Settler::make_convergence_check(const SettleParams &params, long movable,
                                                 double mean_height_start)
{
  if (movable < 1) throw_outside_range("movable", movable, "[1, +inf)");
  // 'stop drift' never stops before `window` checks: a window beyond the cap would run every
  // redeposition to the cap, warning each time that <Z> did not converge.
  if (params.stop == StopRule::Drift && params.drift_window > params.max_checks)
    throw std::invalid_argument(
        "window = " + std::to_string(params.drift_window) + " checks of 'stop drift' is more "
        "than the cap allows (" + std::to_string(params.max_checks) + " checks: maxsweeps "
        "over the check interval), so the rule could never stop before the cap; lower window "
        "or raise maxsweeps");
  const long interval = trials_per_check(params.check_interval, movable);
  return ConvergenceCheck(params.stop, params.eta, params.max_checks, mean_height_start,
                          static_cast<double>(interval) / static_cast<double>(movable),
                          params.drift_window, defaults::kSettleDriftConfidence);
}

long Settler::max_checks_for_sweeps(long max_sweeps, long check_interval, long movable)
{
  check_check_interval(check_interval);
  if (max_sweeps < 1) throw_outside_range("maxsweeps", max_sweeps, "[1, +inf)");
  if (movable < 1) return 1;  // nothing moves: one (empty) check
  const long interval = trials_per_check(check_interval, movable);
  // The cap in trials, saturated: maxsweeps 5e16 of 200 spheres must not wrap to a few sweeps.
  const long most = std::numeric_limits<long>::max();
  const long max_trials = max_sweeps > most / movable ? most : max_sweeps * movable;
  // A check interval beyond the cap would run its whole first check past it (a check of 9e18
  // trials never ends): refused, naming both.
  if (interval > max_trials)
    throw std::invalid_argument(
        "check = " + std::to_string(interval) + " trials exceeds the cap of maxsweeps = " +
        std::to_string(max_sweeps) + " sweeps of " + std::to_string(movable) +
        " movable spheres (" + std::to_string(max_trials) + " trials): the first <Z> check "
        "would come after the cap; lower check or raise maxsweeps");
  return max_trials / interval + (max_trials % interval != 0 ? 1 : 0);
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
  if (n < 0) throw_outside_range("n", n, "[0, +inf)");
  if (n > 0 && (!xyz || !radius))
    throw std::invalid_argument("xyz and radius must not be null when n > 0");
  const Scene scene = make_scene(radius, n, box, params.contact_tol);
  for (int d = 0; d < 2; ++d)
    if (scene.periodic[d] && !(params.d_max < scene.length[d]))
      throw_outside_range("dmax", params.d_max,
                          "(0, periodic length) = (0, " + number(scene.length[d]) + ")");

  movable_ids_.clear();
  for (int i = 0; i < n; ++i)
    if (!movable || movable[i]) movable_ids_.push_back(i);
  SettleResult result;
  const long m = static_cast<long>(movable_ids_.size());
  result.movable = m;
  if (m == 0) return result;
  if (static_cast<std::uint64_t>(m) >= (std::uint64_t{1} << 32))
    throw_outside_range("number of movable spheres", m, "[0, 2^32)");

  if (!sampler_ || sampler_->d_max() != params.d_max ||
      sampler_->theta_sampler().theta0() != params.theta0 ||
      sampler_->theta_sampler().law() != params.theta_law)
    sampler_ = std::make_unique<TrialMoveSampler>(params.d_max, params.theta0, params.theta_law);
  mover_->reset(xyz, radius, n, box, params.d_max, params.contact_tol);
  if (m > 0) mover_->prepare_candidates(movable_ids_.data(), m);

  TrialTally tally;  // sum_dz starts at the sum of the heights: it then holds the sum of <Z>
  for (int i : movable_ids_) tally.sum_dz += xyz[3 * i + 2] - box.floor_z;
  result.mean_height_start = tally.sum_dz / static_cast<double>(m);
  ConvergenceCheck stop = make_convergence_check(params, m, result.mean_height_start);
  const CounterRandom rng(params.seed, RandomPurpose::kSettleMoves, params.stream);
  const long interval = trials_per_check(params.check_interval, m);
  long sweep_cursor = 0;
  for (;;) {
    const long accepted_before = tally.accepted;
    mover_->run(movable_ids_.data(), m, params.order, sweep_cursor, *sampler_, rng,
                static_cast<std::uint64_t>(tally.trials), interval, nullptr, tally);
    // <Z> check every interval (section II), by the rule of tapmc_stop_rule.h.
    const ConvergenceCheck::Verdict verdict = stop.after_check(
        tally.sum_dz / static_cast<double>(m), tally.accepted - accepted_before, interval);
    if (verdict == ConvergenceCheck::Verdict::Converged) break;
    if (verdict == ConvergenceCheck::Verdict::HitCap) {
      result.hit_cap = true;
      break;
    }
  }

  double sum = 0.0;
  for (int i : movable_ids_) {
    const double *p = mover_->position(i);
    for (int d = 0; d < 3; ++d) xyz[3 * i + d] = p[d];
    sum += xyz[3 * i + 2] - box.floor_z;
    if (image_shift_xy) {
      image_shift_xy[2 * i] += mover_->image_shift(i, 0);
      image_shift_xy[2 * i + 1] += mover_->image_shift(i, 1);
    }
  }
  result.trials = tally.trials;
  result.accepted = tally.accepted;
  result.checks = stop.checks();
  result.stopped_on_idle_check = stop.stopped_on_idle_check();
  result.mean_height = sum / static_cast<double>(m);
  result.list_updates = mover_->local_updates();
  result.mean_list_length = mover_->mean_list_length();
  result.list_widenings = mover_->capacity_grows();
  return result;
}

Violation Settler::find_violation(const double *xyz, const double *radius, int n,
                                  const SettleBox &box, double contact_tol)
{
  check_contact_tol(contact_tol);
  if (n < 0) throw_outside_range("n", n, "[0, +inf)");
  Violation v;
  if (n == 0) return v;
  if (!xyz || !radius) throw std::invalid_argument("xyz and radius must not be null when n > 0");
  Scene sc = make_scene(radius, n, box, contact_tol);
  thread_local ViolationScratch scratch;
  // Positions with periodic axes wrapped into the box.
  std::vector<double> &wrapped = scratch.wrapped;
  wrapped.assign(xyz, xyz + 3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      if (sc.periodic[d]) {
        int image = 0;
        wrapped[3 * i + d] = wrap_periodic(xyz[3 * i + d], sc.lo[d], sc.hi[d], sc.length[d], image);
      }
  CellGrid &grid = scratch.grid;
  // Cells one contact distance (plus the rounding margin) wide.
  const double reach = 2.0 * sc.r_max * sc.one_minus_tol + rounding_margin(sc, xyz, n);
  grid.build(grid_axes(sc, xyz, n, reach), wrapped.data(), radius, n);
  for (int i = 0; i < n; ++i) {
    const double x = wrapped[3 * i], y = wrapped[3 * i + 1], z = wrapped[3 * i + 2];
    const double r = radius[i];
    double gap;
    int code = plane_violation<false, false>(sc, x, y, z, r, gap);
    if (!code) code = container_violation(sc, x, y, r, gap);
    if (code) {
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
