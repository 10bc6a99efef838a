// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The box every TAPMC style needs, checked in one place: orthogonal, with a non-periodic z
// (a floor below, an open top above).
#ifndef TAPMC_LAMMPS_BOX_H
#define TAPMC_LAMMPS_BOX_H

#include "tapmc_contact.h"

#include "domain.h"
#include "error.h"
#include "lammps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tapmc {

// Domain::boundary[dim][side] codes of a fixed ('f') and a shrink-wrapped ('s') face.
constexpr int kBoundaryFixed = 1;
constexpr int kBoundaryShrink = 2;

// Stops with a message naming the style (e.g. "fix mc/settle") and what to change.
inline void require_box_with_floor(LAMMPS_NS::LAMMPS *lmp, const char *style)
{
  if (lmp->domain->dimension != 3)  // 2d makes z periodic: the advice below could not be taken
    lmp->error->all(FLERR, "{}: needs a 3d simulation ('dimension 3', the default): the spheres "
                    "rest on a floor normal to z", style);
  if (lmp->domain->triclinic)
    lmp->error->all(FLERR, "{}: triclinic boxes are not supported; use an orthogonal box", style);
  if (lmp->domain->zperiodic)
    lmp->error->all(FLERR, "{}: the z boundary is periodic; the packing needs a floor and an open "
                    "top: use e.g. 'boundary p p fm' (or 'f f fm')", style);
}

// Stops when the box reaches coordinates where a double cannot resolve the contact of the
// smallest spheres (radius `r_min`) to the contact tolerance, naming the axis, the coordinate
// and the bound (tapmc_contact.h, largest_exact_coordinate). A radius that is not positive is
// left to the style's own check of the radii.
// Stops when `what` (e.g. "the box reaches x", "the floor z") = `value` lies beyond that bound.
inline void require_exact_coordinate(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *what,
                                     char axis, double value, double r_min)
{
  if (!(r_min > 0.0)) return;
  const double bound = largest_exact_coordinate(2.0 * r_min);
  if (!(std::fabs(value) > bound)) return;
  lmp->error->all(FLERR, "{}: {} = {}, where doubles are {:.2g} apart: the contacts of spheres "
                  "of radius {} cannot be resolved to the contact tolerance ({} of their contact "
                  "distance) beyond |{}| = {:.3g}, {:.3g} times that radius; move the box and "
                  "the floor nearer the origin (e.g. the floor at z = 0), or make the smallest "
                  "spheres larger (radius, dispersity)", style, what, value,
                  std::fabs(value) * std::numeric_limits<double>::epsilon(), r_min,
                  defaults::kContactTolerance, axis, bound, bound / r_min);
}

inline void require_exact_coordinates(LAMMPS_NS::LAMMPS *lmp, const char *style, double r_min)
{
  const LAMMPS_NS::Domain *domain = lmp->domain;
  for (int d = 0; d < 3; ++d) {
    const double far = std::fabs(domain->boxlo[d]) > std::fabs(domain->boxhi[d])
                           ? domain->boxlo[d] : domain->boxhi[d];
    const std::string what = std::string("the box reaches ") + "xyz"[d];
    require_exact_coordinate(lmp, style, what.c_str(), "xyz"[d], far, r_min);
  }
}

}  // namespace tapmc

#endif
