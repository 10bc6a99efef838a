// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The rounds of the domain-decomposed redeposition: which of its own spheres each rank may move
// at the same time as the others, and where, so that no two ranks ever move interacting spheres
// at once. LAMMPS-free (no MPI): fix mc/settle draws the cuts, calls these functions on every
// rank and communicates between rounds.
//
// The scheme. Along every axis that is split among ranks (or periodic with one rank, when the
// caller lets the rank border its own periodic image through ghosts; fix mc/settle handles such
// an axis by the nearest image in the kernel instead), each rank's sub-domain [lo, lo + w) is
// cut at lo + c into a lower and an
// upper part; c is drawn anew for every cycle of rounds and is the same on every rank. A cycle
// has one round per combination of parts (2 rounds for one such axis, 4 for two, 8 for three).
// In a round a rank moves only the spheres that were in that round's parts at the start of the
// cycle (each sphere of a rank is active in exactly one round of a cycle), and a trial is
// rejected when its new centre leaves the round's region:
//     lower part: [lo - e, lo + c + e),   upper part: [lo + c - e, lo + w + e)
// (e = margin, so spheres cross the cut and the sub-domain faces, in the round where they are
// active; a sphere reaches a region's edge only by travelling e within one round).
// With contact = the largest contact distance 2 R_max and
//     contact + 2e <= c <= w_min - contact - 2e
// (w_min = the narrowest sub-domain along the axis), two regions of the same round on
// neighbouring ranks, or on a rank and its own periodic image, are at least `contact` apart:
// lower regions by w - c - 2e, upper regions by c - 2e. Spheres of different ranks that move in
// the same round therefore never touch, and a rank sees the others' spheres near its region as
// LAMMPS ghosts that do not move during the round (refreshed between rounds). The cost: trials
// that would cross a region edge are rejected in that round; averaged over the random cuts no
// place is special, and every sphere is picked with the same probability as in the serial
// random pick (round_trials), since each is active once per cycle.
#ifndef TAPMC_DECOMPOSITION_H
#define TAPMC_DECOMPOSITION_H

#include "tapmc_sphere_mover.h"

#include <array>
#include <cstdint>

namespace tapmc {

// One axis of this rank's sub-domain.
struct DecomposedAxis {
  bool split = false;     // split among ranks, or periodic: cut into two parts
  double lo = 0, hi = 0;  // this rank's sub-domain along the axis
  double min_width = 0;   // the narrowest sub-domain along the axis over all ranks
};

class RoundSchedule {
 public:
  // contact: the largest contact distance (2 R_max); margin: e above. Throws
  // std::invalid_argument naming the axis when a split axis is narrower than min_width().
  RoundSchedule(const std::array<DecomposedAxis, 3> &axes, double contact, double margin);

  // Narrowest sub-domain the scheme allows along a split axis: 2 contact + 4 margin.
  static double min_width(double contact, double margin);

  static constexpr int kMaxRounds = 8;     // three split axes
  int rounds() const { return rounds_; }  // 2^(number of split axes)

  // A new cycle: the cut of split axis d at lo + contact + 2e + uniform[d] * (allowed range),
  // uniform[d] in [0, 1) drawn identically on every rank.
  void start_cycle(const std::array<double, 3> &uniform);

  // The round in which a sphere at xyz is active this cycle (bit k = upper part of the k-th
  // split axis). Spheres outside the sub-domain (moved there within their margin) count in the
  // part on their side.
  int round_of(const double *xyz) const
  {
    int round = 0;
    for (int k = 0; k < split_count_; ++k) {
      const int d = split_axis_[k];
      round |= static_cast<int>(xyz[d] >= cut_[d]) << k;
    }
    return round;
  }

  // Where the active spheres of `round` may go (unbounded along axes that are not split).
  MoveRegion region(int round) const;

  double cut(int axis) const { return cut_[axis]; }
  // The sub-domain the rounds were laid out on (rebuild the schedule when it changes, e.g. a
  // shrink-wrapped box top that moved at a migration).
  const DecomposedAxis &axis(int d) const { return axes_[d]; }

 private:
  std::array<DecomposedAxis, 3> axes_;
  double contact_, margin_;
  int rounds_ = 1;
  int split_axis_[3] = {-1, -1, -1};  // the split axes in order; split_count_ of them
  int split_count_ = 0;
  std::array<double, 3> cut_{};  // absolute cut position per split axis
};

// Trials a rank makes in one round. The cycle's active spheres are numbered over all (round,
// rank) pairs, round first; this pair holds the `active` spheres after the first `before`. Its
// share of the check's trials is floor((before + active) I / N) - floor(before I / N) (I =
// trials_per_check, N = movable_total): the shares of a cycle add up to I exactly, and each is
// active * I / N to within one trial, so each sphere expects I / N picks per cycle, as in the
// serial uniform pick. (Rounding each share alone lost the check: 16 shares of 0.31 trials
// made 0 trials a cycle, and the redeposition never stopped.) With I = N (one sweep a check,
// the default) the share is `active`.
long round_trials(long before, long active, long trials_per_check, long movable_total);

// Trial moves of sub-domain s in the decomposed redeposition: purpose kDomainSettleMoves
// (tapmc_random.h) under the key round (s + 1) * 2^32 (CounterRandom::round): each
// sub-domain's overflow rounds (fewer than 2^32) never reach another one's key.
inline std::uint64_t sub_domain_key_index(int sub_domain)
{
  return (static_cast<std::uint64_t>(sub_domain) + 1) << 32;
}

// The number of the sub-domain at `loc` in a `grid` of sub-domains, z fastest: the rank that
// LAMMPS's default mapping ('processors ... map cart', MPI_Cart_create without reordering)
// gives it. Keyed by this number rather than by the rank, the trial moves of a sub-domain do
// not depend on which rank holds it ('map xyz', a restart read under another mapping).
inline int sub_domain_number(const int loc[3], const int grid[3])
{
  return (loc[0] * grid[1] + loc[1]) * grid[2] + loc[2];
}

}  // namespace tapmc

#endif
