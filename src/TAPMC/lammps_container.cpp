// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The keyword 'container REGION-ID': a LAMMPS cylinder region read as tapmc::Cylinder, checked.
//
// RegCylinder keeps its centre, radius and axis private. Every LAMMPS version TAPMC builds
// against (29 Sep 2021, its PLUGIN build, the current one) has the same public Region members
// used here: style, interior, open_faces, dynamic, moveflag, rotateflag, varshape, bboxflag, the
// extent_* bounding box, and inside(). An interior cylinder with axis z has the bounding box
// [c1 - R, c1 + R] x [c2 - R, c2 + R] in x and y, so the centre and radius follow from it; equal
// x and y widths then leave only an x or y axis of length 2R, which the probes of the wall
// below tell apart.
#include "lammps_container.h"

#include "lammps_box.h"
#include "lammps_compat.h"

#include "compute.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "modify.h"
#include "region.h"

#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

using LAMMPS_NS::LAMMPS;

namespace tapmc {
namespace {

// Two widths computed from the same centre and radius differ by rounding only; an axis along
// x or y gives the cylinder's length in one of them, which no input sets equal to 2R within
// 1e-12 by accident (and if it does, the probes decide).
constexpr double kExtentAgreement = 1e-12;
// The probes stand this fraction of the radius inside and outside the expected wall: far above
// the rounding of a point's coordinates, far below any gap between a disk and a rectangle.
constexpr double kProbeOffset = 1e-6;
constexpr int kProbeDirections = 8;
// The centre and radius recomputed from the extents differ from the region's own by at most two
// roundings of |c| + R each way (c -+ R, then their sum or difference): four DBL_EPSILON bound
// them with room.
constexpr double kRecoveryRoundings = 4.0;

// Whether the region's points near the expected wall are those of a vertical cylinder of this
// centre and radius: inside at (1 - offset) R, outside at (1 + offset) R, in 8 directions at the
// middle height of the region. A cylinder along x or y whose length happens to equal its
// diameter has a square cross-section in x-y there, so its diagonal probes outside the disk
// land inside it. inside() rather than match(): the region is static and interior (checked
// before), where the two agree, and match() answers 1 everywhere when an end cap is open.
bool wall_is_vertical_cylinder(LAMMPS_NS::Region *region, const Cylinder &c)
{
  const double z = 0.5 * (region->extent_zlo + region->extent_zhi);
  for (int k = 0; k < kProbeDirections; ++k) {
    const double angle = kTwoPi * k / kProbeDirections;
    const double ux = std::cos(angle), uy = std::sin(angle);
    const double in = c.radius * (1.0 - kProbeOffset), out = c.radius * (1.0 + kProbeOffset);
    if (!region->inside(c.cx + in * ux, c.cy + in * uy, z)) return false;
    if (region->inside(c.cx + out * ux, c.cy + out * uy, z)) return false;
  }
  return true;
}

// The value the input most likely gave: the shortest decimal (1 to 17 significant digits) within
// `bound` of `value`. The centre and the radius are recovered from the extents c -+ R that
// LAMMPS rounded, so they carry errors of a few roundings of |c| + R (0.4 comes back as
// 0.40000000000000036 from a centre at 5); the input's own decimal is within that bound and
// gives messages and the disk area pi R^2 exactly as typed.
double typed_value(double value, double bound)
{
  char text[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    const double candidate = std::strtod(text, nullptr);
    if (std::fabs(candidate - value) <= bound) return candidate;
  }
  return value;
}

// The styles that take 'container', as the mismatch message lists them.
constexpr const char *kContainerStyles =
    "fix tapdilate, fix mc/settle, compute stereo/profile; compute contacts counts the wall with "
    "it";

std::string holding(const char *kind, const char *id, const char *style,
                    const std::string &region)
{
  return std::string(kind) + " " + id + " (" + style + ") has " +
         (region.empty() ? std::string("no container") : kContainerKeyword + (" " + region));
}

}  // namespace

Cylinder container_cylinder(LAMMPS *lmp, const char *style, const std::string &id)
{
  LAMMPS_NS::Error *error = lmp->error;
  const char *key = kContainerKeyword;
  LAMMPS_NS::Region *region = compat::find_region(lmp->domain, id);
  if (!region)
    error->all(FLERR,
               "{}: {} = {}: no region with this ID; allowed: the ID of a region defined as "
               "'region {} cylinder z c1 c2 radius lo hi'",
               style, key, id, id);
  const std::string region_style = region->style;
  if (region_style != "cylinder")
    error->all(FLERR,
               "{}: {} = {}: region style '{}' has no exact container test here; allowed: "
               "cylinder with axis z",
               style, key, id, region_style);
  if (!region->interior)
    error->all(FLERR,
               "{}: {} = {}: the region is 'side out' (the space outside the cylinder); "
               "allowed: cylinder with axis z and side in (the default)",
               style, key, id);
  // face 3 of a cylinder is its curved surface; open end caps (faces 1, 2) change nothing here
  if (region->openflag && region->open_faces[2])
    error->all(FLERR,
               "{}: {} = {}: the region's curved wall is open ('open 3'); allowed: a cylinder "
               "with a closed wall (open end caps are ignored)",
               style, key, id);
  if (region->dynamic || region->moveflag || region->rotateflag)
    error->all(FLERR,
               "{}: {} = {}: the region moves or rotates ('move' / 'rotate'); allowed: a fixed "
               "cylinder with axis z",
               style, key, id);
  if (region->varshape)
    error->all(FLERR,
               "{}: {} = {}: the region's centre or radius is a variable (v_name), so it may "
               "change in time; allowed: a cylinder with constant c1, c2 and radius",
               style, key, id);
  if (!region->bboxflag)
    error->all(FLERR, "{}: {} = {}: the region has no bounding box; allowed: cylinder with axis z",
               style, key, id);

  const double wx = region->extent_xhi - region->extent_xlo;
  const double wy = region->extent_yhi - region->extent_ylo;
  Cylinder c;
  c.cx = 0.5 * (region->extent_xlo + region->extent_xhi);
  c.cy = 0.5 * (region->extent_ylo + region->extent_yhi);
  c.radius = 0.25 * (wx + wy);
  // a few roundings of the extents (each within DBL_EPSILON / 2 of |c| + R, relative)
  const double scale = std::max(std::fabs(c.cx), std::fabs(c.cy)) + c.radius;
  const double bound = kRecoveryRoundings * DBL_EPSILON * scale;
  c.cx = typed_value(c.cx, bound);
  c.cy = typed_value(c.cy, bound);
  c.radius = typed_value(c.radius, bound);
  const bool widths_agree = std::fabs(wx - wy) <= kExtentAgreement * std::max(wx, wy);
  if (!widths_agree || !(c.radius > 0.0) || !wall_is_vertical_cylinder(region, c))
    error->all(FLERR,
               "{}: {} = {}: the cylinder's axis is not z (its bounding box is {} wide in x and "
               "{} in y{}); allowed: cylinder with axis z ('region {} cylinder z c1 c2 radius "
               "lo hi')",
               style, key, id, wx, wy,
               widths_agree ? ", but its wall is not a vertical circle" : "", id);
  return c;
}

void require_container_in_box(LAMMPS *lmp, const char *style, const std::string &id,
                              const Cylinder &c)
{
  const LAMMPS_NS::Domain *domain = lmp->domain;
  const char *key = kContainerKeyword;
  if (domain->xperiodic || domain->yperiodic)
    lmp->error->all(FLERR,
                    "{}: {} = {}: the container needs non-periodic x and y (boundary f f ...), "
                    "the box is periodic in {}: the cylinder's wall replaces the periodic sides",
                    style, key, id,
                    domain->xperiodic && domain->yperiodic ? "x and y"
                                                           : (domain->xperiodic ? "x" : "y"));
  // 's' shrinks the box to the spheres at every setup, inside the cylinder: this check passes at
  // the first run's init and fails at the next (the box shrank since)
  for (int d = 0; d < 2; ++d)
    if (domain->boundary[d][0] == kBoundaryShrink || domain->boundary[d][1] == kBoundaryShrink)
      lmp->error->all(FLERR,
                      "{}: {} = {}: the {} boundary is shrink-wrapped ('s'), which shrinks the "
                      "box to the spheres, inside the cylinder; use 'f' (the box holds the "
                      "cylinder) or 'm' with the box's bounds as its minimum",
                      style, key, id, "xy"[d]);
  const double centre[2] = {c.cx, c.cy};
  for (int d = 0; d < 2; ++d) {
    // the region's extent is centre -+ radius as LAMMPS computed it; ours is recomputed from
    // it, hence the slack of a few roundings
    const double slack = kExtentAgreement * (std::fabs(centre[d]) + c.radius);
    const double lo = centre[d] - c.radius, hi = centre[d] + c.radius;
    if (lo < domain->boxlo[d] - slack || hi > domain->boxhi[d] + slack)
      lmp->error->all(FLERR,
                      "{}: {} = {}: the cylinder (centre ({}, {}), radius {}) reaches {} from {} "
                      "to {}, outside the box ({} from {} to {}); allowed: a cylinder within the "
                      "box's x and y ranges",
                      style, key, id, c.cx, c.cy, c.radius, "xy"[d], lo, hi, "xy"[d],
                      domain->boxlo[d], domain->boxhi[d]);
  }
}

void require_container_fits(LAMMPS *lmp, const char *style, const std::string &id,
                            const Cylinder &c, double max_sphere_radius)
{
  std::string message;
  try {
    validate(c, max_sphere_radius);
    return;
  } catch (const std::invalid_argument &e) {
    message = e.what();
  }
  lmp->error->all(FLERR, "{}: {} = {}: {}", style, kContainerKeyword, id, message);
}

Cylinder resolve_container(LAMMPS *lmp, const char *style, const std::string &id,
                           double max_sphere_radius)
{
  const Cylinder c = container_cylinder(lmp, style, id);
  require_container_in_box(lmp, style, id, c);
  if (max_sphere_radius > 0.0) require_container_fits(lmp, style, id, c, max_sphere_radius);
  return c;
}

void require_one_container(LAMMPS *lmp, const char *kind, const char *id, const char *style,
                           const ContainerHolder &self)
{
  const std::string &mine = self.container_region();
  auto compare = [&](const char *other_kind, const char *other_id, const char *other_style,
                     const ContainerHolder *other) {
    if (!other || other == &self) return;
    const std::string &theirs = other->container_region();
    if (theirs == mine) return;
    const bool one_missing = mine.empty() || theirs.empty();
    const ContainerHolder &without = mine.empty() ? self : *other;
    if (one_missing && without.container_optional()) return;
    const std::string pair = holding(kind, id, style, mine) + ", " +
                             holding(other_kind, other_id, other_style, theirs);
    if (one_missing)
      lmp->error->all(FLERR,
                      "{} {}: container missing on one of the styles of a run: {} (a style "
                      "without it takes the box for the container); give the same '{} {}' to "
                      "every TAPMC style of the run ({})",
                      kind, style, pair, kContainerKeyword, mine.empty() ? theirs : mine,
                      kContainerStyles);
    lmp->error->all(FLERR,
                    "{} {}: two different containers in one run: {}; give the same '{} ID' ({} "
                    "or {}) to every TAPMC style of the run ({})",
                    kind, style, pair, kContainerKeyword, mine, theirs, kContainerStyles);
  };
  double my_floor = 0.0;
  const bool has_floor = self.bed_floor(my_floor);
  auto compare_floor = [&](const char *other_kind, const char *other_id, const char *other_style,
                           const ContainerHolder *other) {
    double theirs = 0.0;
    if (!has_floor || !other || other == &self || !other->bed_floor(theirs)) return;
    const double scale = std::max({1.0, std::fabs(my_floor), std::fabs(theirs)});
    if (std::fabs(my_floor - theirs) <= defaults::kFloorMatchTolerance * scale) return;
    lmp->error->all(FLERR,
                    "{} {}: two different floors in one run: {} {} ({}) has floor {}, {} {} ({}) "
                    "has floor {}; give the same 'floor z0' to every TAPMC style of the run (a "
                    "style without 'floor' takes the box's lower z bound when it is defined)",
                    kind, style, kind, id, style, my_floor, other_kind, other_id, other_style,
                    theirs);
  };
  auto compare_walls = [&](const char *other_kind, const char *other_id, const char *other_style,
                           const ContainerHolder *other) {
    if (!other || other == &self) return;
    for (int d = 0; d < 2; ++d) {
      double lo = 0.0, hi = 0.0, their_lo = 0.0, their_hi = 0.0;
      if (!self.side_walls(d, lo, hi) || !other->side_walls(d, their_lo, their_hi)) continue;
      const double scale = std::max({1.0, std::fabs(lo), std::fabs(hi), std::fabs(their_lo),
                                     std::fabs(their_hi)});
      const double tol = defaults::kFloorMatchTolerance * scale;
      if (std::fabs(lo - their_lo) <= tol && std::fabs(hi - their_hi) <= tol) continue;
      lmp->error->all(FLERR,
                      "{} {}: two different side walls along {} in one run: {} {} ({}) has them "
                      "at {} = {} and {}, {} {} ({}) at {} and {}; a style without '{}walls' "
                      "takes the box faces, and compute stereo/profile always does (it would "
                      "divide by the box's width): make the box faces the walls ('boundary f' "
                      "with the box from {} to {}), or give every style the box faces",
                      kind, style, "xy"[d], kind, id, style, "xy"[d], lo, hi, other_kind,
                      other_id, other_style, their_lo, their_hi, "xy"[d],
                      std::max(lo, their_lo), std::min(hi, their_hi));
    }
  };
  double my_radius = 0.0;
  const bool has_radius = self.keyword_radius(my_radius);
  auto compare_radius = [&](const char *other_kind, const char *other_id, const char *other_style,
                            const ContainerHolder *other) {
    double theirs = 0.0;
    if (!has_radius || !other || other == &self || !other->keyword_radius(theirs)) return;
    if (std::fabs(my_radius - theirs) <= defaults::kRadiusMatchTolerance * my_radius) return;
    if (lmp->comm->me == 0)  // a compute measuring other spheres: strange, not harmful
      lmp->error->warning(FLERR,
                          "{} {}: two different sphere radii in one run: {} {} ({}) takes radius "
                          "{}, {} {} ({}) radius {} (from their 'diameter' / 'radius' "
                          "keywords): the second measures spheres the run does not hold; give "
                          "every TAPMC style of the run the same radius",
                          kind, style, kind, id, style, my_radius, other_kind, other_id,
                          other_style, theirs);
  };
  auto compare_all = [&](const char *other_kind, const char *other_id, const char *other_style,
                         const ContainerHolder *other) {
    compare(other_kind, other_id, other_style, other);
    compare_radius(other_kind, other_id, other_style, other);
    compare_floor(other_kind, other_id, other_style, other);
    compare_walls(other_kind, other_id, other_style, other);
  };
  LAMMPS_NS::Modify *modify = lmp->modify;
  for (int i = 0; i < modify->nfix; ++i) {
    LAMMPS_NS::Fix *fix = modify->fix[i];
    compare_all("fix", fix->id, fix->style, dynamic_cast<const ContainerHolder *>(fix));
  }
  for (int i = 0; i < modify->ncompute; ++i) {
    LAMMPS_NS::Compute *compute = modify->compute[i];
    compare_all("compute", compute->id, compute->style,
                dynamic_cast<const ContainerHolder *>(compute));
  }
}

}  // namespace tapmc
