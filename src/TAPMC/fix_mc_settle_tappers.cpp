// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle and the run's tapping fixes (tapmc::Tapper, lammps_tapper.h): which they are,
// that they are still those of the run's setup, and the step of the next redeposition
// (fix_mc_settle.cpp runs the redeposition); the run's other fixes that move atoms; and the
// tapped atoms that no fix mc/settle redeposits.
#include "fix_mc_settle.h"

#include "lammps_tapper.h"

#include "comm.h"
#include "error.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

// The run's fixes that move atoms besides the taps and the redeposition, as "ID (style)": those
// LAMMPS calls to integrate (an integrator, fix move, fix wall/reflect), those that move or
// insert atoms between steps (fix deform's remap, gcmc, pour, deposit), and fix adapt, which
// can grow the radii (atom diameter) into overlaps. A lid of wall/reflect reflected
// spheres lifted by a tap back into the bed, and a leftover fix nve/sphere moved them by their
// velocities: overlaps, silently (the redeposition keeps overlaps it starts with). Such a run
// is checked before each tap (pre_exchange).
std::string FixMCSettle::other_fixes_moving_atoms() const
{
  constexpr int kMoves = FixConst::INITIAL_INTEGRATE | FixConst::POST_INTEGRATE |
                         FixConst::FINAL_INTEGRATE;
  const std::vector<std::string> moving_styles = {"adapt", "deform", "deposit", "gcmc", "pour"};
  std::string names;
  for (int i = 0; i < modify->nfix; ++i) {
    Fix *fix = modify->fix[i];
    const bool tapmc_style = dynamic_cast<tapmc::Tapper *>(fix) || std::strcmp(fix->style, style) == 0;
    // a dynamic group's own fix (style GROUP) updates membership, never positions
    if (std::strcmp(fix->style, "GROUP") == 0) continue;
    const std::string fix_style = fix->style;
    const std::string base = fix_style.substr(0, fix_style.find('/'));
    const bool moves = (modify->fmask[i] & kMoves) ||
                       std::find(moving_styles.begin(), moving_styles.end(), base) !=
                           moving_styles.end();
    if (tapmc_style || !moves) continue;
    names += (names.empty() ? "" : ", ") + std::string(fix->id) + " (" + fix->style + ")";
  }
  return names;
}

// The run's tapping fixes (fix tapdilate or any tapmc::Tapper), in definition order.
void FixMCSettle::find_tappers()
{
  tappers.clear();
  tapper_ids.clear();
  for (int i = 0; i < modify->nfix; ++i)
    if (auto *tapper = dynamic_cast<tapmc::Tapper *>(modify->fix[i])) {
      tappers.push_back(tapper);
      tapper_ids.emplace_back(modify->fix[i]->id);
    }
}

// A run with 'pre no' skips init(): a tapping fix deleted (or defined) since the last setup
// would leave a dangling pointer (or never tap). Stop instead, naming the fixes.
void FixMCSettle::require_same_tappers()
{
  std::vector<std::string> now;
  std::vector<tapmc::Tapper *> found;
  bool all_scheduled = true;
  for (int i = 0; i < modify->nfix; ++i)
    if (auto *tapper = dynamic_cast<tapmc::Tapper *>(modify->fix[i])) {
      now.emplace_back(modify->fix[i]->id);
      found.push_back(tapper);
      all_scheduled = all_scheduled && tapper->scheduled();
    }
  if (now == tapper_ids && found == tappers && all_scheduled) return;
  auto names = [](const std::vector<std::string> &ids) {
    std::string s;
    for (const std::string &id : ids) s += (s.empty() ? "" : ", ") + id;
    return s.empty() ? std::string("none") : s;
  };
  error->all(FLERR, "fix mc/settle: the tapping fixes changed since the run's setup (then: {}; "
             "now: {}), and this run skipped the setup ('run ... pre no'); run with 'pre yes' "
             "(the default) after defining or deleting a fix", names(tapper_ids),
             names(now) + (now == tapper_ids ? ", defined again since" : ""));
}

// The first step after `after` on which a tapping fix taps (any fix, whatever its order), or
// simply the step after it when the run has no tapping fix.
void FixMCSettle::schedule_next_settle(bigint after)
{
  next_reneighbor = after + 1;
  if (tappers.empty()) return;
  next_reneighbor = tappers.front()->next_tap_after(after);
  for (const tapmc::Tapper *tap : tappers)
    next_reneighbor = std::min(next_reneighbor, tap->next_tap_after(after));
}

// The group bits of every fix mc/settle of the run (fixes on disjoint groups are allowed).
int FixMCSettle::settled_group_bits() const
{
  int bits = 0;
  for (int i = 0; i < modify->nfix; ++i)
    if (std::strcmp(modify->fix[i]->style, style) == 0) bits |= modify->fix[i]->groupbit;
  return bits;
}

// Atoms a tap lifts that no fix mc/settle redeposits (`adrift`, counted in init) rise by eps
// times their height at every tap, for ever (a rough floor of fixed spheres tapped with 'fix
// tapdilate all'): warned once, by the run's first fix mc/settle.
void FixMCSettle::warn_tapped_never_redeposited(long adrift)
{
  if (adrift == 0 || comm->me != 0 || warned_adrift) return;
  for (int i = 0; i < modify->nfix; ++i)  // the first fix mc/settle warns, not every one
    if (std::strcmp(modify->fix[i]->style, style) == 0) {
      if (modify->fix[i] != this) return;
      break;
    }
  warned_adrift = true;
  std::string tapping;
  for (const std::string &tapper_id : tapper_ids)
    tapping += (tapping.empty() ? "" : ", ") + tapper_id;
  error->warning(FLERR, "fix mc/settle: {} atom(s) are tapped (fix {}) but in the group of no "
                 "fix mc/settle: nothing redeposits them, so each tap lifts them by eps times "
                 "their height above the floor, tap after tap. Tap only the settled spheres "
                 "(fix tapdilate on the group of fix mc/settle) or put them in its group",
                 adrift, tapping);
}
