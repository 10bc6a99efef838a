// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Rounds of the domain-decomposed redeposition (the scheme and its proof: tapmc_decomposition.h).
#include "tapmc_decomposition.h"

#include "tapmc_checks.h"
#include "tapmc_math.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
const char *const kAxisName[3] = {"x", "y", "z"};
}  // namespace

double RoundSchedule::min_width(double contact, double margin)
{
  return 2.0 * contact + 4.0 * margin;
}

RoundSchedule::RoundSchedule(const std::array<DecomposedAxis, 3> &axes, double contact,
                             double margin)
    : axes_(axes), contact_(contact), margin_(margin)
{
  if (!(contact > 0.0 && std::isfinite(contact)))
    throw_outside_range("contact distance", contact, "(0, +inf)");
  if (!(margin >= 0.0 && std::isfinite(margin)))
    throw_outside_range("margin", margin, "[0, +inf)");
  const double needed = min_width(contact, margin);
  for (int d = 0; d < 3; ++d) {
    if (!axes[d].split) continue;
    if (!(axes[d].hi > axes[d].lo) || !(axes[d].min_width <= axes[d].hi - axes[d].lo))
      throw std::invalid_argument(std::string("sub-domain along ") + kAxisName[d] + " [" +
                                  number(axes[d].lo) + ", " + number(axes[d].hi) +
                                  ") is empty or narrower than the given narrowest width " +
                                  number(axes[d].min_width));
    if (axes[d].min_width < needed)
      throw std::invalid_argument(
          std::string("the narrowest sub-domain along ") + kAxisName[d] + " is " +
          number(axes[d].min_width) + " wide; the decomposed redeposition needs at least " +
          number(needed) + " (2 contact distances + 4 move margins)");
    split_axis_[split_count_++] = d;
    cut_[d] = 0.5 * (axes[d].lo + axes[d].hi);
  }
  rounds_ = 1 << split_count_;
}

void RoundSchedule::start_cycle(const std::array<double, 3> &uniform)
{
  for (int k = 0; k < split_count_; ++k) {
    const int d = split_axis_[k];
    const double first = contact_ + 2.0 * margin_;
    const double range = axes_[d].min_width - contact_ - 2.0 * margin_ - first;  // >= 0
    cut_[d] = axes_[d].lo + first + uniform[d] * range;
  }
}

MoveRegion RoundSchedule::region(int round) const
{
  MoveRegion r{{-kInf, -kInf, -kInf}, {kInf, kInf, kInf}};
  for (int k = 0; k < split_count_; ++k) {
    const int d = split_axis_[k];
    if ((round >> k) & 1) {
      r.lo[d] = cut_[d] - margin_;
      r.hi[d] = axes_[d].hi + margin_;
    } else {
      r.lo[d] = axes_[d].lo - margin_;
      r.hi[d] = cut_[d] + margin_;
    }
  }
  return r;
}

long round_trials(long before, long active, long trials_per_check, long movable_total)
{
  if (movable_total <= 0 || active <= 0 || trials_per_check <= 0) return 0;
  if (trials_per_check == movable_total) return active;
  // floor(c I / N) in 128 bits: c and I reach 2^31 and more.
  const auto trials_before = [&](long c) {
    return static_cast<long>(static_cast<__int128>(c) * trials_per_check / movable_total);
  };
  return trials_before(before + active) - trials_before(before);
}

}  // namespace tapmc
