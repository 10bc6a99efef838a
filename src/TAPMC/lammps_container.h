// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The keyword 'container REGION-ID' of the TAPMC styles: a LAMMPS region resolved into the
// vertical cylinder of tapmc_cylinder.h, its checks against the spheres and the box, and one
// container for all the styles of a run.
//
// The paper taps in a box (section II); a tube is the other container of compaction
// experiments. Its wall is taken from a region so that the input names the container once, in
// LAMMPS' own terms ('region tube cylinder z c1 c2 radius lo hi'), and every style reads the
// same wall. Only what the TAPMC kernels compute exactly is accepted: an interior cylinder with
// axis z, fixed in time. Its end caps (lo, hi; INF or EDGE allowed) play no part: the floor is
// the styles' own 'floor', the top is open.
#ifndef TAPMC_LAMMPS_CONTAINER_H
#define TAPMC_LAMMPS_CONTAINER_H

#include "tapmc_cylinder.h"

#include "lammps.h"

#include <string>

namespace tapmc {

// The keyword's name, as every style spells it in its table and its messages.
constexpr const char *kContainerKeyword = "container";

// The cylinder of region `region_id`. Stops (error->all, collective: every rank sees the same
// regions) with a message naming `style`, the keyword, the value and what is allowed, when the
// region does not exist, is not style cylinder, has an axis other than z, is 'side out', has an
// open curved wall ('open 3'), moves or rotates, or has a variable centre or radius.
Cylinder container_cylinder(LAMMPS_NS::LAMMPS *lmp, const char *style,
                            const std::string &region_id);

// The container and the box agree: x and y are not periodic (the wall replaces the periodic
// sides), and the cylinder lies within the box's x and y ranges (to rounding). Stops naming
// both otherwise.
void require_container_in_box(LAMMPS_NS::LAMMPS *lmp, const char *style,
                              const std::string &region_id, const Cylinder &cylinder);

// The container is wider than its largest sphere (tapmc::validate(cylinder, r_max)); stops
// naming the region and both radii otherwise. r_max must be > 0.
void require_container_fits(LAMMPS_NS::LAMMPS *lmp, const char *style,
                            const std::string &region_id, const Cylinder &cylinder,
                            double max_sphere_radius);

// All three, in that order: what a style calls when it is defined and again in init() (the
// region may have been deleted or redefined, the box changed, the radii set). max_sphere_radius
// <= 0 (no spheres yet) skips the last check.
Cylinder resolve_container(LAMMPS_NS::LAMMPS *lmp, const char *style,
                           const std::string &region_id, double max_sphere_radius);

// ---- one container per run ----------------------------------------------------------------------
// A TAPMC style that takes 'container' (fix tapdilate, fix mc/settle, compute stereo/profile,
// compute contacts) says which region it was given, so that the styles of a run can be compared
// (require_one_container): each resolves its own container and cannot see that another style
// of the run has none, or another one, while each alone is valid. A compute stereo/profile
// without the container of the run's fix mc/settle would divide by the box's area instead of
// the disk's, silently.
class ContainerHolder {
 public:
  // The region ID given with 'container', or empty: the box is the container.
  virtual const std::string &container_region() const = 0;
  // Whether this style may leave out the run's container: true when without it the style
  // measures something else rather than something wrong (compute contacts without 'container'
  // counts contacts between spheres only, as it leaves out the floor without 'floor'). Its
  // container, when it has one, must still be the run's.
  virtual bool container_optional() const { return false; }
  // The floor plane z0 the style moves or measures the bed from ('floor', default the box's
  // lower z bound when the style was defined), if it has one (compute contacts without
  // 'floor' has none): the styles of a run must agree (require_one_container), since a tap
  // about another floor lifts the bed by eps times the gap and a compute stereo/profile with
  // another floor measures an empty slab (Phi_b 0 for a floor 2 below the bed).
  virtual bool bed_floor(double & /*z0*/) const { return false; }
  // The side walls along x (dim 0) or y (dim 1) the style moves or measures the bed between,
  // if it has walls there: fix mc/settle's 'xwalls'/'ywalls' or the fixed box faces, compute
  // stereo/profile's box faces. The styles of a run must agree (require_one_container): every
  // fix mc/settle of the run, and a compute stereo/profile, which between the box faces of a bed
  // held by narrower walls divides by the box's area (Phi half the packing's for walls at half
  // the box width).
  virtual bool side_walls(int /*dim*/, double & /*lo*/, double & /*hi*/) const { return false; }
  // The sphere radius the style's keyword gives (fix mc/settle 'diameter'/2, the computes'
  // 'radius'), if given. Per-atom radii, where the atom style has them, are compared with it
  // (check_radius_keyword_against_atoms); without them the styles of a run are compared with
  // one another (require_one_container warns): a compute measuring spheres of another radius
  // than those settled reports another packing.
  virtual bool keyword_radius(double & /*radius*/) const { return false; }

 protected:
  ~ContainerHolder() = default;  // never deleted through this interface: LAMMPS owns the style
};

// Compares the container of `self` (the style `kind` ("fix" or "compute") `id` of style
// `style`) with that of every other fix and compute of the run that is a ContainerHolder, and
// stops (error->all: every rank holds the same styles) naming both styles, their regions (or
// "no container") and what to do when one has a container and the other none (unless that one
// is optional), or the two have different regions; and the same for their floors (bed_floor)
// and their side walls (side_walls) where both have them. fix mc/settle calls it in init(): every tapping run has one.
void require_one_container(LAMMPS_NS::LAMMPS *lmp, const char *kind, const char *id,
                           const char *style, const ContainerHolder &self);

}  // namespace tapmc

#endif
