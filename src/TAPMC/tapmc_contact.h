// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Hard-sphere contact predicates with the relative contact tolerance (the overlap rule of
// doc/fix_mc_settle.rst, "Description"), written once so the Monte Carlo kernel and the
// violation check do identical arithmetic.
#ifndef TAPMC_CONTACT_H
#define TAPMC_CONTACT_H

#include "tapmc_defaults.h"

#include <cmath>
#include <limits>

namespace tapmc {

// Largest |coordinate| at which a double still resolves a contact of `contact_distance` to the
// relative contact tolerance (tapmc_defaults.h, kCoordinateRoundingMargin).
inline double largest_exact_coordinate(double contact_distance,
                                       double contact_tol = defaults::kContactTolerance)
{
  return contact_tol * contact_distance /
         (defaults::kCoordinateRoundingMargin * std::numeric_limits<double>::epsilon());
}

// Squared distance, written once with explicit fused operations so every caller (vectorised
// kernel loop, scalar violation check, benchmarks) rounds identically.
inline double distance_sq(double dx, double dy, double dz)
{
#ifdef __FMA__
  return std::fma(dz, dz, std::fma(dy, dy, dx * dx));
#else
  return dx * dx + dy * dy + dz * dz;
#endif
}

// Pair overlap: |r_ij| < (R_i + R_j)(1 - tol). Squared threshold for one pair.
inline double overlap_threshold_sq(double r_i, double r_j, double one_minus_tol)
{
  const double reach = (r_i + r_j) * one_minus_tol;
  return reach * reach;
}

// Separation of j from i along one axis, with the periodic image shift of j (0 or +-L) added
// last: sep(i, j) = -sep(j, i) exactly, so a pair tested from either side gives the same
// squared distance, bit for bit.
inline double separation(double x_j, double x_i, double image_shift)
{
  return (x_j - x_i) + image_shift;
}

// The impassable planes, numbered once for every kernel and message: where a partner index j
// names a sphere when j >= 0, a negative j names one of these planes (the deposition's
// constraints, a violation found by the Monte Carlo kernel).
enum PlaneId : int {
  kFloorPlane = -1,  // z = z_floor, below
  kWallXlo = -2,     // x = low x wall (non-periodic x)
  kWallXhi = -3,     // x = high x wall
  kWallYlo = -4,     // y = low y wall (non-periodic y)
  kWallYhi = -5,     // y = high y wall
  kCylinderWall = -6,  // the wall of a cylindrical container (tapmc_cylinder.h)
};
// The two side walls of axis 0 (x) or 1 (y).
inline PlaneId low_wall(int axis) { return axis == 0 ? kWallXlo : kWallYlo; }
inline PlaneId high_wall(int axis) { return axis == 0 ? kWallXhi : kWallYhi; }
// As messages name it: "the floor", "the low x wall", ...
inline const char *plane_name(PlaneId plane)
{
  switch (plane) {
    case kFloorPlane: return "the floor";
    case kWallXlo: return "the low x wall";
    case kWallXhi: return "the high x wall";
    case kWallYlo: return "the low y wall";
    case kWallYhi: return "the high y wall";
    case kCylinderWall: return "the cylinder wall";
  }
  return "an unknown plane";
}

// Plane constraints (floor below, side walls): the sphere's surface may reach a plane up to
// tol * (2R) beyond it. `gap` = distance from the plane to the sphere surface (< 0: overlap).
inline bool gap_violates(double gap, double r, double tol)
{
  return gap < -tol * (2.0 * r);
}
inline double floor_gap(double z, double r, double floor_z) { return (z - r) - floor_z; }
inline double low_wall_gap(double x, double r, double wall) { return (x - r) - wall; }
inline double high_wall_gap(double x, double r, double wall) { return wall - (x + r); }

// The side wall of one axis that a sphere (coordinate c along the axis, radius r) crosses beyond
// the tolerance, the low one first, with its gap; 0 when it crosses neither.
inline int side_wall_violation(int axis, double c, double r, double wall_lo, double wall_hi,
                               double tol, double &gap)
{
  gap = low_wall_gap(c, r, wall_lo);
  if (gap_violates(gap, r, tol)) return low_wall(axis);
  gap = high_wall_gap(c, r, wall_hi);
  if (gap_violates(gap, r, tol)) return high_wall(axis);
  return 0;
}

}  // namespace tapmc

#endif
