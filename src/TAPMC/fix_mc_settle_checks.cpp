// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle: what is wrong with its input or its start, and the messages that say so (a
// step of a whole period, an atom without a radius, an overlapping or misplaced sphere);
// fix_mc_settle.cpp runs the redeposition.
#include "fix_mc_settle.h"

#include "lammps_support.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
#include "tapmc_settle.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

namespace {
const char *const kAxisName[2] = {"x", "y"};
}  // namespace

// A 'dmax' of a whole period or more along a periodic side (here and in init: change_box can
// shrink the box). The kernels refuse it too, but scheme domain meets it only after the first
// tap's thermo, on every rank whose sub-domain spans that period, without the fix's name.
void FixMCSettle::check_dmax_against_periods() const
{
  if (!dmax_given) return;  // the default follows the radius, below any legal period
  for (int d = 0; d < 2; ++d)
    if (domain->periodicity[d] && !(d_max < domain->prd[d]))
      error->all(FLERR, "fix mc/settle: {}",
                 tapmc::outside_range_message(
                     "dmax", tapmc::number(d_max),
                     fmt::format("(0, periodic length along {}) = (0, {})", kAxisName[d],
                                 tapmc::number(domain->prd[d]))));
}

// Every atom, in the group or a fixed obstacle outside it, is a sphere of positive radius: the
// first atom (by ID) that is not is named on every rank, as scheme gather names it (the kernel
// would stop later on the rank that holds it, with its internal index). Collective.
void FixMCSettle::require_positive_radii() const
{
  if (fixed_radius > 0.0) return;  // the keyword's radius for every atom
  const double *radius = atom->radius;
  const tapmc::FirstAtom bad =
      tapmc::first_atom_where(lmp, [&](int i) { return !(radius[i] > 0.0); });
  if (bad.tag < 0) return;
  error->all(FLERR, "fix mc/settle: atom {} has radius {}; every sphere needs a radius > 0 (set "
             "it with atom_style sphere / set diameter, or the 'diameter' keyword)",
             bad.tag, bad.radius);
}

// What is wrong with a start configuration: an overlapping pair, a sphere below the floor or
// through a side wall (plane numbering of tapmc_contact.h).
std::string FixMCSettle::violation_message(const tapmc::Violation &v, tagint tag_i,
                                           tagint tag_j, bool after_tap) const
{
  // an overlap found during the run: the pair, then its cause
  const std::string pair = fmt::format("fix mc/settle: step {}: atoms {} and {} overlap by {}",
                                       update->ntimestep, tag_i, tag_j, -v.gap);
  if (v.j >= 0 && checking_other_movers)
    return pair + fmt::format(" before the tap: fix {} move(s) atoms besides the taps and "
                              "pushed a sphere into another (a wall/reflect lid reflects spheres "
                              "lifted by a tap back into the bed; an integrator moves them by "
                              "their velocities); unfix it: hard spheres are moved by fix "
                              "tapdilate and fix mc/settle only", other_movers);
  if (v.j >= 0 && after_tap && every_atom_tapped)
    return pair + " after the tap: every atom is tapped, but by tapping fixes of different "
                  "groups that dilate them differently (another eps, floor or tap schedule), so "
                  "one group's dilation pushed a sphere into one of another group; tap every "
                  "sphere with one tapping fix (group all)";
  if (v.j >= 0 && after_tap)
    return pair + fmt::format(" after the tap: part of the bed stands still (atoms outside the "
                              "group of fix {} or of a tapping fix), and the tap's dilation "
                              "pushed a sphere into one that did not follow it; tap and "
                              "redeposit every sphere (group all), or keep the spheres that "
                              "stand still below those that move", id);
  if (v.j >= 0)
    return fmt::format("fix mc/settle: atoms {} and {} overlap by {} at the start (allowed: a "
                       "relative tolerance of {} of the contact distance); start from a "
                       "non-overlapping packing", tag_i, tag_j, -v.gap,
                       tapmc::defaults::kContactTolerance);
  if (v.j == tapmc::kFloorPlane)
    return fmt::format("fix mc/settle: atom {} reaches {} below the floor z0 = {} (its centre "
                       "must be at least its radius above the floor)", tag_i, -v.gap, z_floor);
  if (v.j == tapmc::kCylinderWall)
    return fmt::format("fix mc/settle: atom {} crosses the wall of container {} by {} (its centre "
                       "must be within the container radius {} minus its own radius of the axis "
                       "x = {}, y = {})", tag_i, container_region_id, -v.gap, container.radius,
                       container.cx, container.cy);
  const bool x_wall = v.j == tapmc::kWallXlo || v.j == tapmc::kWallXhi;
  return fmt::format("fix mc/settle: atom {} crosses a side wall in {} by {} ({})", tag_i,
                     x_wall ? "x" : "y", -v.gap,
                     tapmc::plane_name(static_cast<tapmc::PlaneId>(v.j)));
}
