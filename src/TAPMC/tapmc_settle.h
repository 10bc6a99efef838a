// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The redeposition (paper, section II): downward-biased hard-sphere Monte Carlo until the mean
// height <Z> stops changing. LAMMPS-free kernel behind fix mc/settle. The trials run on the
// trial-move engine (tapmc_sphere_mover.h): neighbour lists with a skin, kept up to date
// locally, exact (they never miss an overlap), so the moves never depend on the skin.
#ifndef TAPMC_SETTLE_H
#define TAPMC_SETTLE_H

#include "tapmc_defaults.h"
#include "tapmc_settle_types.h"
#include "tapmc_stop_rule.h"
#include "tapmc_trial_move.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace tapmc {

class SphereMover;

struct SettleParams {
  double d_max;            // absolute step length bound, > 0
  double theta0;           // width of P(theta), in (0, defaults::kThetaWidthMax]
  ThetaLaw theta_law = ThetaLaw::Angle;  // P(theta) per unit theta or per unit solid angle
  double eta;              // stop when |<Z>_now - <Z>_before| / <Z>_before < eta, in (0, 1), and
                           // the packing is no longer in free fall (kSettleFreeFallAcceptance)
  long check_interval = 0; // trials between <Z> checks; 0 = number of movable spheres (1 sweep)
  long max_checks;         // cap on check intervals per redeposition (reported, never silent);
                           // from a cap in sweeps: Settler::max_checks_for_sweeps
  double contact_tol;      // relative tolerance (defaults::kContactTolerance)
  std::uint64_t seed;      // user seed
  std::uint64_t stream;    // e.g. the LAMMPS timestep of this tap: keys the random numbers
  PickOrder order = PickOrder::Random;
  // How eta is applied (tapmc_stop_rule.h): Change = the paper's change between two checks;
  // Drift = the drift per sweep averaged over drift_window checks (>= 2) plus
  // defaults::kSettleDriftConfidence standard errors, below eta <Z>.
  StopRule stop = StopRule::Change;
  long drift_window = defaults::kSettleDriftWindow;
};

struct SettleResult {
  long trials = 0, accepted = 0, checks = 0;
  double mean_height_start = 0, mean_height = 0;  // <Z> of movable spheres above floor_z
  bool hit_cap = false;
  // The paper's rule stopped at a check that accepted no trial (ConvergenceCheck::
  // stopped_on_idle_check): a stop by chance, not by convergence.
  bool stopped_on_idle_check = false;
  long movable = 0;  // number of movable spheres
  // Neighbour-list upkeep in this call (diagnostics only, results do not depend on the skin):
  // local list updates (a sphere moved skin/2 from where its list was made), widenings of the
  // list rows (a list outgrew its row: O(N), rare) and the mean list length at the end.
  long list_updates = 0, list_widenings = 0;
  double mean_list_length = 0.0;
};

// j >= 0 sphere, else the PlaneId crossed (tapmc_contact.h); gap < 0 = overlap depth
struct Violation {
  int i = -1, j = -1;
  double gap = 0;
};

class Settler {
 public:
  Settler();
  ~Settler();
  Settler(const Settler &) = delete;
  Settler &operator=(const Settler &) = delete;

  // One complete redeposition (paper, section II) of the n spheres in xyz (interleaved x,y,z;
  // modified in place). radius[n] per sphere (all equal -> monodisperse fast path chosen once).
  // movable[n] nonzero = may move (nullptr = all); the others are fixed obstacles.
  // Throws std::invalid_argument for bad parameters (message names the parameter, value, range).
  // Precondition: no violation beyond contact_tol (the caller checks with find_violation).
  // Movable spheres come back wrapped into [lo, hi) along periodic axes.
  SettleResult settle(double *xyz, const double *radius, const unsigned char *movable, int n,
                      const SettleBox &box, const SettleParams &params);

  // Same, and adds to image_shift_xy[2i + d] (if not null) the number of periods sphere i was
  // wrapped by along periodic axis d (x_unwrapped = x + image * L, LAMMPS convention), so the
  // caller can keep image flags.
  SettleResult settle(double *xyz, const double *radius, const unsigned char *movable, int n,
                      const SettleBox &box, const SettleParams &params, int *image_shift_xy);

  // The first violation found (overlapping pair incl. periodic images, sphere below floor or
  // beyond a side wall, tolerance as in settle), or i == -1 when none. O(n) with a cell list.
  static Violation find_violation(const double *xyz, const double *radius, int n,
                                  const SettleBox &box, double contact_tol);

  // Throws std::invalid_argument naming the first bad parameter, its value and its allowed
  // range (used by settle, and by fix mc/settle on its arguments at construction).
  static void validate(const SettleParams &params);

  // Trial moves between two <Z> checks: check_interval, or one sweep (`movable`) when it is 0.
  static long trials_per_check(long check_interval, long movable);

  // The stopping rule of one redeposition of `movable` spheres starting at <Z> =
  // mean_height_start, as `params` asks (stop, eta, max_checks, check_interval, drift_window):
  // what settle uses, and what a driver that feeds its own (e.g. globally reduced) <Z> uses to
  // stop alike.
  static ConvergenceCheck make_convergence_check(const SettleParams &params, long movable,
                                                 double mean_height_start);

  // The max_checks that allows max_sweeps sweeps of `movable` spheres (at least one check).
  // Throws std::invalid_argument for check_interval < 0 or max_sweeps < 1.
  static long max_checks_for_sweeps(long max_sweeps, long check_interval, long movable);

  // Skin of the neighbour lists, in units of the largest radius (default
  // defaults::kListSkinOverRadius). Any value > 0 gives bit-identical results; only the speed
  // changes (for tests and benchmarks). Throws std::invalid_argument outside (0, +inf).
  void set_verlet_skin(double skin_over_max_radius);
  double verlet_skin() const { return skin_over_max_radius_; }

 private:
  std::unique_ptr<TrialMoveSampler> sampler_;  // cached while (d_max, theta0, law) stay
  std::unique_ptr<SphereMover> mover_;  // the trial-move engine, storage reused between calls
  std::vector<int> movable_ids_;
  double skin_over_max_radius_;
};

}  // namespace tapmc

#endif
