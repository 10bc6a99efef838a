// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// A vertical cylindrical container: validation, the hard-wall test, sphere-cylinder volumes.
//
// The paper taps in a box with periodic or flat side walls (section II); a tube is the other
// container of compaction experiments. Its wall is one more impassable surface: a sphere of
// radius r is inside when its centre lies within radius - r of the axis, with the contact
// tolerance of the flat walls (tapmc_contact.h). The exact stereology in the tube (Phi(z) over
// the disk, radial profiles, the wall zone of FIG. 8) needs the volume of a sphere inside a
// coaxial cylinder, computed here (one sphere) and summed in tapmc_stereology.h.
#ifndef TAPMC_CYLINDER_H
#define TAPMC_CYLINDER_H

#include "tapmc_contact.h"

#include <cmath>
#include <vector>

namespace tapmc {

// Axis along z through (cx, cy); the wall is the surface at distance `radius` from the axis.
struct Cylinder {
  double cx = 0.0;
  double cy = 0.0;
  double radius = 1.0;
};

// Throws std::invalid_argument (tapmc_checks.h phrase) unless the centre is finite and the
// radius finite and > 0; names "cylinder cx", "cylinder cy" or "cylinder radius".
void validate(const Cylinder &cylinder);
// The same, and the container must be wider than its largest sphere: radius > max_sphere_radius
// (a sphere of radius r fits only within radius - r of the axis). max_sphere_radius must be > 0.
void validate(const Cylinder &cylinder, double max_sphere_radius);

// ---- the hard wall ------------------------------------------------------------------------------
// The flat walls (gap_violates of tapmc_contact.h) let a sphere's surface reach up to
// tol * (2 r) beyond the wall: the tolerance is relative to the sphere's diameter, exactly as
// for the floor. The cylinder takes the same rule with the radial gap
//   gap = (radius - r) - |centre - axis|   (> 0 inside, < 0: the surface is beyond the wall),
// so a sphere is inside when gap >= -tol (2 r), i.e. when its centre is within
//   reach(r) = (radius - r) + tol (2 r)
// of the axis. The hot loop compares squared distances with reach(r)^2 (no square root): for
// reach > 0 both sides are non-negative and squaring keeps the order, and the two tests can only
// differ for centres within ~1e-16 relative of the boundary, far inside the tolerance. reach is
// written (radius - r) + tol (2 r), not radius - r (1 - 2 tol), so that tol = 0 gives exactly
// radius - r (a sphere touching the wall is inside, a hair beyond is not).
inline double cylinder_reach(double cylinder_radius, double r, double tol)
{
  return (cylinder_radius - r) + tol * (2.0 * r);
}
// reach(r)^2, or -1 when reach < 0 (a sphere wider than the container: never inside, since a
// squared distance is never negative).
inline double cylinder_reach_sq(double cylinder_radius, double r, double tol)
{
  const double reach = cylinder_reach(cylinder_radius, r, tol);
  return reach >= 0.0 ? reach * reach : -1.0;
}

// The wall with its tolerance, for the trial-move loop. The squared reach depends only on the
// radius: a monodisperse caller computes it once (reach_sq(r)), a polydisperse one once per
// sphere (reach_sq_table), and the loop calls contains(x, y, reach_sq) with no branch on the
// radii (the voro++ policy split rather than a test inside the loop).
struct CylinderWall {
  double cx = 0.0, cy = 0.0, radius = 1.0;
  double tol = 0.0;

  double axis_distance_sq(double x, double y) const
  {
    const double dx = x - cx, dy = y - cy;
    return dx * dx + dy * dy;
  }
  double reach_sq(double r) const { return cylinder_reach_sq(radius, r, tol); }
  // The one test both the moves and the violation check use (identical arithmetic).
  bool contains(double x, double y, double reach_sq) const
  {
    return axis_distance_sq(x, y) <= reach_sq;
  }
  bool contains_sphere(double x, double y, double r) const { return contains(x, y, reach_sq(r)); }
  // Signed distance from the wall to the sphere's surface (> 0: inside with room; the floor_gap
  // of the flat walls), for diagnostics and messages.
  double gap(double x, double y, double r) const
  {
    return (radius - r) - std::sqrt(axis_distance_sq(x, y));
  }
};

// A validated wall: validate(cylinder, max_sphere_radius) and contact_tol in [0,
// kMaxContactTolerance) (the check of every other wall, settle_geometry::check_contact_tol).
CylinderWall make_cylinder_wall(const Cylinder &cylinder, double max_sphere_radius,
                                double contact_tol);
// reach_sq(radius[i]) for i < n: the per-sphere table of a polydisperse loop.
std::vector<double> reach_sq_table(const CylinderWall &wall, const double *radius, int n);

// The violation check: true when the sphere is NOT inside (the same test as the moves), with its
// gap (as side_wall_violation of tapmc_contact.h reports a flat wall's).
inline bool cylinder_violation(const CylinderWall &wall, double x, double y, double r, double &gap)
{
  gap = wall.gap(x, y, r);
  return !wall.contains_sphere(x, y, r);
}

// ---- one sphere and a coaxial cylinder (the stereology's geometry) ------------------------------
// Area of the intersection of two disks of radii a and b whose centres are d apart (0 when
// either radius is <= 0). Exact closed form (two circular segments), accurate to rounding
// relative to the lens itself, also for thin lenses near tangency.
double disk_lens_area(double a, double b, double d);
// Length of the arc of the circle of radius rho (centre O) inside the disk of radius a whose
// centre is d from O: d/d(rho) of disk_lens_area(a, rho, d).
double circle_arc_in_disk(double rho, double a, double d);

// A sphere of radius R centred at the origin, an infinite vertical cylinder of radius rho whose
// axis passes at horizontal distance d from the sphere's centre, and the slab zlo <= z <= zhi:
// the volume of sphere ∩ cylinder ∩ slab. Closed forms where the sphere is wholly inside or
// outside the cylinder; otherwise the integral over z of disk_lens_area(sqrt(R^2 - z^2), rho, d)
// by Gauss-Legendre on the pieces between the kinks of the integrand (see tapmc_cylinder.cpp),
// accurate to ~1e-15 R^3 (defaults::kCylinderQuadratureNodes).
double sphere_cylinder_slab_volume(double R, double d, double rho, double zlo, double zhi);
// Area of the sphere's material on the cylinder's surface (radius rho) within the slab: the
// derivative of sphere_cylinder_slab_volume with respect to rho (the cut of a coaxial
// cylindrical surface, as a horizontal plane cuts a disk).
double sphere_cylinder_surface_area(double R, double d, double rho, double zlo, double zhi);

}  // namespace tapmc

#endif
