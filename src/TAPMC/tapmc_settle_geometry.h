// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The geometry of the redeposition shared by its kernels (tapmc_settle.cpp,
// tapmc_sphere_mover.cpp): validated box and radii, periodic wraps, plane constraints and the
// nearest-image separation, written once so every kernel does identical arithmetic.
#ifndef TAPMC_SETTLE_GEOMETRY_H
#define TAPMC_SETTLE_GEOMETRY_H

#include "tapmc_cell_grid.h"
#include "tapmc_checks.h"
#include "tapmc_contact.h"
#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
#include "tapmc_settle_types.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {
namespace settle_geometry {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline void check_contact_tol(double contact_tol)
{
  if (!(contact_tol >= 0.0 && contact_tol < defaults::kMaxContactTolerance))
    throw_outside_range("contact_tol", contact_tol,
                        "[0, " + number(defaults::kMaxContactTolerance) + ")");
}

inline void check_check_interval(long check_interval)
{
  if (check_interval < 0)
    throw_outside_range("check", check_interval, "[0, +inf) (0 = one sweep)");
}

// Wraps one trial step (|step| < L) into [lo, hi): at most one period (wrap_periodic of
// tapmc_math.h for any distance).
inline double wrap_step(double x, double lo, double hi, double length, int &image)
{
  if (x < lo) {
    x += length;
    image -= 1;
    if (x >= hi) x = lo;
  } else if (x >= hi) {
    x -= length;
    image += 1;
    if (x < lo) x = lo;
  }
  return x;
}

// Everything about the scene that stays fixed during one call.
struct Scene {
  const double *radius = nullptr;
  bool mono = true;
  double r_mono = 0.0, r_max = 0.0, r_min = 0.0;
  double tol = 0.0, one_minus_tol = 1.0;
  bool periodic[2] = {false, false};
  double lo[2] = {0, 0}, hi[2] = {0, 0}, length[2] = {0, 0};
  // Side planes; -inf / +inf where there is none, so the plane tests never fire.
  double wall_lo[2] = {-kInf, -kInf}, wall_hi[2] = {kInf, kInf};
  double floor_z = 0.0;
  // The cylindrical container, if any (then x and y are not periodic), and the squared reach
  // of a sphere of radius r_mono (the monodisperse loop's one number).
  bool cylinder = false;
  CylinderWall wall;
  double cylinder_reach_sq_mono = 0.0;
};

inline Scene make_scene(const double *radius, int n, const SettleBox &box, double contact_tol)
{
  Scene s;
  s.radius = radius;
  s.tol = contact_tol;
  s.one_minus_tol = 1.0 - contact_tol;
  s.floor_z = box.floor_z;
  if (!std::isfinite(box.floor_z)) throw_outside_range("floor_z", box.floor_z, "(finite)");
  if (n > 0) {
    s.r_min = s.r_max = radius[0];
    for (int i = 0; i < n; ++i) {
      const double r = radius[i];
      if (!(r > 0.0 && std::isfinite(r)))
        throw_outside_range("radius[" + std::to_string(i) + "]", r, "(0, +inf)");
      s.r_min = std::min(s.r_min, r);
      s.r_max = std::max(s.r_max, r);
    }
  }
  s.mono = (s.r_min == s.r_max);
  s.r_mono = s.r_max;
  const char *axis_name[2] = {"x", "y"};
  for (int d = 0; d < 2; ++d) {
    s.periodic[d] = box.periodic[d];
    s.lo[d] = box.lo[d];
    s.hi[d] = box.hi[d];
    if (box.periodic[d]) {
      if (!std::isfinite(box.lo[d]))
        throw_outside_range(std::string("periodic box lo[") + axis_name[d] + "]", box.lo[d],
                            "(finite)");
      if (!(std::isfinite(box.hi[d]) && box.hi[d] > box.lo[d]))
        throw_outside_range(std::string("periodic box hi[") + axis_name[d] + "]", box.hi[d],
                            "(lo, +inf) = (" + number(box.lo[d]) + ", +inf)");
      s.length[d] = box.hi[d] - box.lo[d];
      if (s.length[d] < 2.0 * s.r_max)
        throw_outside_range(std::string("periodic box length ") + axis_name[d], s.length[d],
                            "[2 R_max, +inf) = [" + number(2.0 * s.r_max) + ", +inf)");
      if (box.wall_lo[d] || box.wall_hi[d])
        throw std::invalid_argument(std::string("wall_lo/wall_hi[") + axis_name[d] +
                                    "] set on a periodic axis: walls need a non-periodic axis");
    } else {
      if (box.wall_lo[d]) {
        if (!std::isfinite(box.wall_lo_pos[d]))
          throw_outside_range(std::string("wall_lo_pos[") + axis_name[d] + "]",
                              box.wall_lo_pos[d], "(finite)");
        s.wall_lo[d] = box.wall_lo_pos[d];
      }
      if (box.wall_hi[d]) {
        if (!std::isfinite(box.wall_hi_pos[d]))
          throw_outside_range(std::string("wall_hi_pos[") + axis_name[d] + "]",
                              box.wall_hi_pos[d], "(finite)");
        s.wall_hi[d] = box.wall_hi_pos[d];
      }
      if (box.wall_lo[d] && box.wall_hi[d] && !(box.wall_lo_pos[d] < box.wall_hi_pos[d]))
        throw_outside_range(std::string("wall_hi_pos[") + axis_name[d] + "]", box.wall_hi_pos[d],
                            "(wall_lo_pos, +inf) = (" + number(box.wall_lo_pos[d]) + ", +inf)");
    }
  }
  if (box.cylinder) {
    if (box.periodic[0] || box.periodic[1])
      throw std::invalid_argument(
          "a cylindrical container needs non-periodic x and y (periodic x: " +
          std::string(box.periodic[0] ? "yes" : "no") +
          ", periodic y: " + std::string(box.periodic[1] ? "yes" : "no") + ")");
    const Cylinder cylinder{box.cylinder_cx, box.cylinder_cy, box.cylinder_radius};
    if (n > 0) {
      s.wall = make_cylinder_wall(cylinder, s.r_max, contact_tol);
    } else {
      validate(cylinder);
      s.wall = CylinderWall{cylinder.cx, cylinder.cy, cylinder.radius, contact_tol};
    }
    s.cylinder = true;
    s.cylinder_reach_sq_mono = s.wall.reach_sq(s.r_mono);
  }
  return s;
}

inline double radius_of(const Scene &s, int i) { return s.mono ? s.r_mono : s.radius[i]; }

// The plane constraints (floor, side walls) of a sphere of radius r at (x, y, z): 0 if none is
// violated, else the PlaneId (tapmc_contact.h) of the first, floor then side walls, with its
// gap. A periodic axis has no walls, and the hot loop (which knows its axes at compile time)
// skips their tests.
template <bool PeriodicX, bool PeriodicY>
inline int plane_violation(const Scene &s, double x, double y, double z, double r, double &gap)
{
  gap = floor_gap(z, r, s.floor_z);
  if (gap_violates(gap, r, s.tol)) return kFloorPlane;
  if (!PeriodicX)
    if (const int wall = side_wall_violation(0, x, r, s.wall_lo[0], s.wall_hi[0], s.tol, gap))
      return wall;
  if (!PeriodicY)
    if (const int wall = side_wall_violation(1, y, r, s.wall_lo[1], s.wall_hi[1], s.tol, gap))
      return wall;
  return 0;
}

// The container's wall: kCylinderWall with its gap when the sphere is not inside it, else 0
// (also 0 without a container). The hot loop tests the wall itself, compiled only where there is
// one (tapmc_sphere_mover.cpp).
inline int container_violation(const Scene &s, double x, double y, double r, double &gap)
{
  if (s.cylinder && cylinder_violation(s.wall, x, y, r, gap)) return kCylinderWall;
  return 0;
}

// Separation of j from i along a periodic axis, nearest image: the shift (0 or +-L) is chosen
// from the raw difference and added last, exactly as separation() with a cell's image shift.
inline double nearest_separation(double x_j, double x_i, double length, double half_length)
{
  const double raw = x_j - x_i;
  const double shift = raw > half_length ? -length : (raw < -half_length ? length : 0.0);
  return separation(x_j, x_i, shift);
}

template <bool Periodic>
inline double axis_separation(double x_j, double x_i, double length, double half_length)
{
  return Periodic ? nearest_separation(x_j, x_i, length, half_length) : x_j - x_i;
}

// Rounding margin of a search radius: positions, steps and wraps round at ~1e-16 of the
// coordinates (defaults::kGridRoundingMargin of 2 R_max + the largest coordinate, plane or box
// bound), far below the contact tolerance.
inline double rounding_margin(const Scene &s, const double *xyz, int n)
{
  double scale = std::max(std::fabs(s.floor_z), 2.0 * s.r_max);
  for (int i = 0; i < 3 * n; ++i) scale = std::max(scale, std::fabs(xyz[i]));
  for (int d = 0; d < 2; ++d) scale = std::max({scale, std::fabs(s.lo[d]), std::fabs(s.hi[d])});
  return defaults::kGridRoundingMargin * (2.0 * s.r_max + scale);
}

// Cells at least `reach` wide covering the periodic period, or the data (with the walls and the
// floor: movable spheres only go down, at most to the floor) along the other axes. The cell
// count is capped (a floor far below the spheres must not allocate a huge empty grid).
inline std::array<GridAxis, 3> grid_axes(const Scene &s, const double *xyz, int n, double reach)
{
  double mn[3] = {kInf, kInf, kInf}, mx[3] = {-kInf, -kInf, -kInf};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      mn[d] = std::min(mn[d], xyz[3 * i + d]);
      mx[d] = std::max(mx[d], xyz[3 * i + d]);
    }
  for (int d = 0; d < 2; ++d) {
    if (std::isfinite(s.wall_lo[d])) mn[d] = std::min(mn[d], s.wall_lo[d]);
    if (std::isfinite(s.wall_hi[d])) mx[d] = std::max(mx[d], s.wall_hi[d]);
  }
  if (s.cylinder) {  // the spheres move anywhere inside the disk
    const double centre[2] = {s.wall.cx, s.wall.cy};
    for (int d = 0; d < 2; ++d) {
      mn[d] = std::min(mn[d], centre[d] - s.wall.radius);
      mx[d] = std::max(mx[d], centre[d] + s.wall.radius);
    }
  }
  mn[2] = std::min(mn[2], s.floor_z);
  std::array<GridAxis, 3> axes;
  for (int d = 0; d < 2; ++d) {
    if (s.periodic[d])
      axes[d].setup(s.lo[d], s.length[d], reach, true, defaults::kGridMaxCellsPerSideAxis);
    else
      axes[d].setup(mn[d], std::max(mx[d] - mn[d], 0.0), reach, false,
                    defaults::kGridMaxCellsPerSideAxis);
  }
  const long max_cells = defaults::kGridCellsPerSphere * static_cast<long>(n) +
                         defaults::kGridMinCells;
  const int max_z = static_cast<int>(
      std::max(1L, max_cells / (static_cast<long>(axes[0].cells) * axes[1].cells)));
  axes[2].setup(mn[2], std::max(mx[2] - mn[2], 0.0), reach, false, max_z);
  return axes;
}

}  // namespace settle_geometry
}  // namespace tapmc

#endif
