// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// When a redeposition stops (paper, section II: "until <Z> converges"). One object per
// redeposition, fed the mean height <Z> of the movable spheres at every check; shared by the
// serial kernel (tapmc_settle.cpp) and the domain-decomposed fix, which feeds it the globally
// reduced values, so both stop by the same rule.
#ifndef TAPMC_STOP_RULE_H
#define TAPMC_STOP_RULE_H

#include "tapmc_defaults.h"

#include <cmath>
#include <limits>

namespace tapmc {

class ConvergenceCheck {
 public:
  enum class Verdict { Continue, Converged, HitCap };

  // eta: relative change of <Z> between two checks below which the packing counts as settled;
  // max_checks: cap on the number of checks (the caller reports reaching it).
  ConvergenceCheck(double eta, long max_checks, double mean_height_start)
      : eta_(eta), max_checks_(max_checks), previous_mean_(mean_height_start)
  {
  }

  // One check after `trials` trial moves of which `accepted` were accepted since the previous
  // check: stop when |<Z>_now - <Z>_before| / <Z>_before < eta, unless the packing is still in
  // free fall (at least defaults::kSettleFreeFallAcceptance of the trials accepted: a sphere
  // falling through empty space changes <Z> by a constant relative amount that can be small).
  Verdict after_check(double mean_height, long accepted, long trials)
  {
    ++checks_;
    const double change = std::fabs(mean_height - previous_mean_);
    const double relative =
        previous_mean_ != 0.0 ? change / std::fabs(previous_mean_)
                              : (change == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
    previous_mean_ = mean_height;
    const bool falling = static_cast<double>(accepted) >=
                         defaults::kSettleFreeFallAcceptance * static_cast<double>(trials);
    if (relative < eta_ && !falling) return Verdict::Converged;
    if (checks_ >= max_checks_) return Verdict::HitCap;
    return Verdict::Continue;
  }

  long checks() const { return checks_; }

 private:
  double eta_;
  long max_checks_;
  double previous_mean_;
  long checks_ = 0;
};

}  // namespace tapmc

#endif
