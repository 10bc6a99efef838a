// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The closed-form root finding of the deposition's events along a path: the first entry of
// K + P cos t + Q sin t below zero (every contact and support force along a circle), the sign
// changes of a trigonometric polynomial of degree 2 (the contact functions of the cylinder wall
// and of the roll along it), and the first entry of a contact function sampled between such
// roots. first_entry (hot: every sphere near a roll) is inline and first_entry_scan a template,
// so both are here; the sign changes are in tapmc_deposition_roots.cpp.
#ifndef TAPMC_DEPOSITION_ROOTS_H
#define TAPMC_DEPOSITION_ROOTS_H

#include "tapmc_defaults.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>

namespace tapmc {
namespace deposition_detail {

// First t in [0, t_max] at which f(t) = K + P cos t + Q sin t enters f < 0, or +inf.
// `entering_now` is set when f is negative just after t = 0 (a touching constraint that the
// path enters immediately, to first or second order); a touching constraint being left (its
// negative arc ends within kDepositionAngleTolerance after 0) is not an event.
inline double first_entry(double K, double P, double Q, double t_max, bool &entering_now)
{
  entering_now = false;
  const double A = std::hypot(P, Q);
  // Never deeper than kDepositionGrazingDepth below zero anywhere on the circle (a constraint
  // tangent to the whole path, e.g. a wall containing the rolling plane): not an event.
  if (K - A > -kDepositionGrazingDepth) return kInf;
  const double kappa = -K / A;  // f < 0  <=>  cos(t - beta) < kappa
  if (kappa <= -1.0) return kInf;
  if (kappa >= 1.0) {  // f <= 0 on the whole circle: only possible when touching at its maximum
    entering_now = true;
    return 0.0;
  }
  const double beta = std::atan2(Q, P);
  const double w = std::acos(kappa);
  const double start = wrap_angle(beta + w);  // negative arc: [start, start + length]
  const double length = kTwoPi - 2.0 * w;
  if (start + length > kTwoPi) {  // the negative arc contains t = 0
    const double remaining = start + length - kTwoPi;
    if (remaining > kDepositionAngleTolerance) {
      entering_now = true;
      return 0.0;
    }
  }
  return start <= t_max ? start : kInf;
}

// Where f changes sign in [0, t_max] (t_max <= 2 pi), ascending, at most 4 a quarter turn (the
// array holds 16). On the quarter turn t = s + u, u in [0, pi / 2], f (1 + x^2)^2 with
// x = tan(u / 2) in [0, 1] is a quartic in x of the same sign as f.
int trig2_sign_changes(const Trig2 &f, double t_max, double *roots);

// First entry into gap < 0 along a path t in [0, t_max], for a contact function `gap` (a length:
// > 0 free, < 0 overlap) that keeps its sign between the sorted `breaks` in (0, t_max) (the
// roots of a polynomial that vanishes wherever gap does). Each piece between breaks is sampled
// on gap itself; a piece counts as entered when a sample lies deeper than `grazing` (the
// grazing convention of first_entry). A constraint touching at t = 0 (gap(0) <= touch) whose
// negative arc reaches beyond kDepositionAngleTolerance is entered now (returns 0 with
// `entering_now`); one whose negative arc ends before is being left, not an event. Otherwise the
// entry is refined by bisection on gap and the last point outside is returned; +inf if none.
template <class Gap>
double first_entry_scan(const Gap &gap, double *breaks, int n_breaks, double t_max,
                        double grazing, double touch, bool &entering_now)
{
  entering_now = false;
  std::sort(breaks, breaks + n_breaks);
  const bool touching = gap(0.0) <= touch;
  // A touching constraint: its breaks within the angle tolerance belong to the start.
  int first = 0;
  while (touching && first < n_breaks && breaks[first] <= kDepositionAngleTolerance) ++first;
  double lo = touching ? std::min(kDepositionAngleTolerance, t_max) : 0.0;
  double outside = 0.0;   // last sample point not entered
  bool seen_outside = !touching;
  constexpr int samples = defaults::kDepositionPieceSamples;
  for (int q = first; q <= n_breaks; ++q) {
    const double hi = q < n_breaks ? std::min(breaks[q], t_max) : t_max;
    if (hi > lo) {
      for (int k = 1; k <= samples; ++k) {
        const double t = lo + (hi - lo) * k / (samples + 1);
        const double g = gap(t);
        if (g >= -grazing) {
          outside = t;
          seen_outside = true;
          continue;
        }
        if (!seen_outside) {  // negative from the start beyond the angle tolerance
          entering_now = true;
          return 0.0;
        }
        const double g_out = gap(outside);
        const double target = std::min(0.0, 0.5 * g_out);
        double t0 = outside, t1 = t;
        for (;;) {
          const double mid = 0.5 * (t0 + t1);
          if (!(mid > t0 && mid < t1)) break;
          if (gap(mid) >= target) {
            t0 = mid;
          } else {
            t1 = mid;
          }
        }
        return t0;
      }
    }
    lo = std::max(lo, hi);
  }
  return kInf;
}

}  // namespace deposition_detail
}  // namespace tapmc

#endif
