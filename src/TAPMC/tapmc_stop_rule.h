// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// When a redeposition stops (paper, section II: "until <Z> converges"). One object per
// redeposition, fed the mean height <Z> of the movable spheres at every check; shared by the
// serial kernel (tapmc_settle.cpp) and the domain-decomposed fix, which feeds it the globally
// reduced values, so both stop by the same rule.
//
// Two rules, both with the threshold eta on a relative change of <Z>:
//   Change (the paper's, the default): |<Z>_now - <Z>_before| / <Z>_before < eta between two
//     consecutive checks. The change over one check is a noisy estimate of the drift of <Z>
//     (its standard deviation goes as 1/sqrt(N)), so the rule stops at the first check that is
//     low by chance: earlier in a small packing than in a large one at the same eta.
//   Drift: the drift of <Z> per sweep, averaged over the last `window` checks, plus `confidence`
//     standard errors of that average, below eta <Z>. The noise then delays the stop instead of
//     triggering it, and the stopping sweep tends, at every N, to the sweep where the mean drift
//     of <Z> (an intensive property of the packing) crosses eta.
#ifndef TAPMC_STOP_RULE_H
#define TAPMC_STOP_RULE_H

#include "tapmc_defaults.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace tapmc {

enum class StopRule { Change, Drift };

class ConvergenceCheck {
 public:
  enum class Verdict { Continue, Converged, HitCap };

  // The paper's rule. eta: relative change of <Z> between two checks below which the packing
  // counts as settled; max_checks: cap on the number of checks (the caller reports reaching it).
  ConvergenceCheck(double eta, long max_checks, double mean_height_start)
      : ConvergenceCheck(StopRule::Change, eta, max_checks, mean_height_start, 1.0, 1, 0.0)
  {
  }

  // Either rule. sweeps_per_check: trials between two checks over the number of movable spheres
  // (> 0; converts a change per check into a drift per sweep); window (>= 2) and confidence
  // (>= 0): the Drift rule's number of checks averaged and standard errors added (unused by
  // Change).
  ConvergenceCheck(StopRule rule, double eta, long max_checks, double mean_height_start,
                   double sweeps_per_check, long window, double confidence)
      : rule_(rule), eta_(eta), max_checks_(max_checks), previous_mean_(mean_height_start),
        sweeps_per_check_(sweeps_per_check), confidence_(confidence)
  {
    if (rule_ == StopRule::Drift) decrements_.assign(static_cast<std::size_t>(window), 0.0);
  }

  // One check after `trials` trial moves of which `accepted` were accepted since the previous
  // check. Neither rule stops while the packing is still in free fall (at least
  // defaults::kSettleFreeFallAcceptance of the trials accepted: a sphere falling through empty
  // space changes <Z> by a constant relative amount that can be small).
  Verdict after_check(double mean_height, long accepted, long trials)
  {
    ++checks_;
    const bool settled = rule_ == StopRule::Change ? change_below_eta(mean_height)
                                                   : drift_below_eta(mean_height);
    previous_mean_ = mean_height;
    const bool falling = static_cast<double>(accepted) >=
                         defaults::kSettleFreeFallAcceptance * static_cast<double>(trials);
    if (settled && !falling) {
      stopped_on_idle_check_ = rule_ == StopRule::Change && accepted == 0;
      return Verdict::Converged;
    }
    if (checks_ >= max_checks_) return Verdict::HitCap;
    return Verdict::Continue;
  }

  long checks() const { return checks_; }

  // Change rule: true when the check that stopped the redeposition accepted no trial. When one
  // accepted move changes <Z> by more than eta (a bed of a few dozen spheres at eta = 1e-7),
  // that is the only way the rule can stop: the stop then comes where a check of so many
  // trials happens to accept none, whatever eta.
  bool stopped_on_idle_check() const { return stopped_on_idle_check_; }

  // Drift rule: the latest estimate of the drift of <Z> per sweep (mean decrement over the
  // window) and its standard error; both 0 until the window is full, and for the Change rule.
  double drift_per_sweep() const { return drift_; }
  double drift_standard_error() const { return drift_error_; }

 private:
  // |<Z>_now - <Z>_before| / <Z>_before < eta
  bool change_below_eta(double mean_height) const
  {
    const double change = std::fabs(mean_height - previous_mean_);
    const double relative =
        previous_mean_ != 0.0 ? change / std::fabs(previous_mean_)
                              : (change == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
    return relative < eta_;
  }

  // (|mean decrement per sweep| + confidence * its standard error) / <Z>_now < eta, over the
  // last `window` checks (never before the window is full).
  bool drift_below_eta(double mean_height)
  {
    const std::size_t window = decrements_.size();
    decrements_[static_cast<std::size_t>(checks_ - 1) % window] =
        (previous_mean_ - mean_height) / sweeps_per_check_;
    if (static_cast<std::size_t>(checks_) < window) return false;
    double sum = 0.0;
    for (double d : decrements_) sum += d;
    const double mean = sum / static_cast<double>(window);
    double squares = 0.0;
    for (double d : decrements_) squares += (d - mean) * (d - mean);
    drift_ = mean;
    drift_error_ = std::sqrt(squares / static_cast<double>(window - 1) /
                             static_cast<double>(window));
    const double bound = std::fabs(drift_) + confidence_ * drift_error_;
    const double height = std::fabs(mean_height);
    return height != 0.0 ? bound / height < eta_ : bound == 0.0;
  }

  StopRule rule_;
  double eta_;
  long max_checks_;
  double previous_mean_;
  double sweeps_per_check_;
  double confidence_;
  std::vector<double> decrements_;  // Drift: decrement of <Z> per sweep of the last checks (ring)
  double drift_ = 0.0, drift_error_ = 0.0;
  long checks_ = 0;
  bool stopped_on_idle_check_ = false;
};

}  // namespace tapmc

#endif
