// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The sequential deposition's paths from one point (the method: tapmc_deposition.cpp's header
// comment): the descent at a point from the touching constraints alone (the KKT conditions), the
// searches of the deposited spheres (what touches a point, where a drop starts, the next event
// along a fall or a roll) and the roll of one segment on one sphere or on two constraints.
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_deposition_grid.h"
#include "tapmc_deposition_roots.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tapmc {
namespace deposition_detail {

// ---------------------------------------------------------------------------------------------
// The descent at a point (the KKT conditions of tapmc_deposition.cpp's header comment), from the
// contacts alone.

namespace {

// Projection of gravity onto the subspace tangent to the selected normals; feasible when the
// support forces are >= 0 and the direction enters no other touching constraint.
bool feasible(const std::vector<Vec3> &normals, const int *sel, int size, Vec3 &d)
{
  const int n = static_cast<int>(normals.size());
  const double tol = kDepositionForceTolerance;
  double mu[3] = {0, 0, 0};
  if (size == 0) {
    d = kGravity;
  } else if (size == 1) {
    const Vec3 a = normals[sel[0]];
    mu[0] = -dot(a, kGravity);
    d = kGravity + mu[0] * a;
  } else if (size == 2) {
    const Vec3 a = normals[sel[0]], b = normals[sel[1]];
    const double c = dot(a, b), det = 1.0 - c * c;
    // (anti)parallel normals: a smaller set covers it
    if (det < defaults::kDepositionParallelNormals) return false;
    const double ga = dot(a, kGravity), gb = dot(b, kGravity);
    mu[0] = -(ga - c * gb) / det;
    mu[1] = -(gb - c * ga) / det;
    d = kGravity + mu[0] * a + mu[1] * b;
    d = d - dot(d, a) * a;  // remove rounding along the normals
    d = d - dot(d, b) * b;
  } else {
    const Vec3 a = normals[sel[0]], b = normals[sel[1]], c = normals[sel[2]];
    const double det = dot(a, cross(b, c));
    // coplanar normals: no isolated rest point
    if (std::fabs(det) < defaults::kDepositionCoplanarNormals) return false;
    // Solve a mu0 + b mu1 + c mu2 = -g (Cramer), d = 0.
    const Vec3 h = -1.0 * kGravity;
    mu[0] = dot(h, cross(b, c)) / det;
    mu[1] = dot(a, cross(h, c)) / det;
    mu[2] = dot(a, cross(b, h)) / det;
    d = {0, 0, 0};
  }
  for (int a = 0; a < size; ++a)
    if (mu[a] < -tol) return false;
  for (int k = 0; k < n; ++k) {
    if (std::find(sel, sel + size, k) != sel + size) continue;
    if (dot(normals[k], d) < -tol) return false;
  }
  return true;
}

// Active set and descent direction (KKT of the projection of gravity onto the cone of
// feasible directions). Subsets are tried from the smallest: at a point where a support
// force is exactly zero, the smaller set (the support is being left) wins. Subsets must

}  // namespace

// contain every constraint of `forced` (indices into `contacts` of the constraints the previous
// path entered at once).
Descent solve_descent(const ContactSet &contacts, const std::vector<int> &forced)
{
  const int n = contacts.size();
  Descent out;
  auto attempt = [&](const int *sel, int size) {
    for (int f : forced)
      if (std::find(sel, sel + size, f) == sel + size) return false;
    Vec3 d;
    if (!feasible(contacts.normals, sel, size, d)) return false;
    out.found = true;
    out.n_active = size;
    for (int a = 0; a < size; ++a) out.active[a] = sel[a];
    out.d = d;
    return true;
  };
  int sel[3] = {-1, -1, -1};
  if (attempt(sel, 0)) return out;
  for (sel[0] = 0; sel[0] < n; ++sel[0])
    if (attempt(sel, 1)) return out;
  for (sel[0] = 0; sel[0] < n; ++sel[0])
    for (sel[1] = sel[0] + 1; sel[1] < n; ++sel[1])
      if (attempt(sel, 2)) return out;
  for (sel[0] = 0; sel[0] < n; ++sel[0])
    for (sel[1] = sel[0] + 1; sel[1] < n; ++sel[1])
      for (sel[2] = sel[1] + 1; sel[2] < n; ++sel[2])
        if (attempt(sel, 3)) return out;
  return out;
}

// Whether moving from the current point along dir would enter a touching constraint that is
// not active (to first order).
bool blocked(Vec3 dir, const ContactSet &contacts, const Descent &descent)
{
  const std::vector<Vec3> &normals = contacts.normals;
  for (std::size_t k = 0; k < normals.size(); ++k) {
    const int ki = static_cast<int>(k);
    if (std::find(descent.active, descent.active + descent.n_active, ki) !=
        descent.active + descent.n_active)
      continue;
    if (dot(normals[k], dir) < -kDepositionForceTolerance) return true;
  }
  return false;
}

// ---------------------------------------------------------------------------------------------
// Searches of the deposited spheres and the planes: what touches a point, where a drop starts,
// and the next event along a fall or a roll.

// Fills `contacts` with the spheres and planes within kDepositionSupportTolerance of contact
// with a sphere (p, r) (its previous content is discarded; the caller reuses its storage).
void collect_touching(const DepositedSpheres &packing, Vec3 p, double r, ContactSet &contacts)
{
  std::vector<Constraint> &touching = contacts.constraints;
  touching.clear();
  contacts.normals.clear();
  const LayeredGrid &grid = packing.grid;
  const double reach = (r + packing.r_max) * (1.0 + 2.0 * kDepositionSupportTolerance);
  grid.visit(p.x - reach, p.x + reach, p.y - reach, p.y + reach, grid.layer_of(p.z - reach),
             grid.layer_of(p.z + reach),
             [&](std::int32_t i, double sx, double sy, int ix, int iy) {
               const Vec3 c = packing.centre_of(i) + Vec3{sx, sy, 0.0};
               const double dist = r + packing.radii[i];
               const Vec3 delta = p - c;
               const double d2 = dot(delta, delta);
               const double limit = dist * (1.0 + kDepositionSupportTolerance);
               if (d2 > limit * limit) return;
               touching.push_back(Constraint{true, i, ix, iy, c, dist});
             });
  packing.for_each_plane(r, [&](const Constraint &k) {
    if (gap_of(k, p) <= kDepositionSupportTolerance * 2.0 * r) touching.push_back(k);
  });
  if (packing.domain.has_cylinder) {
    const Constraint wall = packing.cylinder_wall(r);
    if (gap_of(wall, p) <= kDepositionSupportTolerance * 2.0 * r) touching.push_back(wall);
  }
  for (const auto &k : touching) contacts.normals.push_back(normal_of(k, p));
}

// Start of a drop at (x, y): just above every sphere whose column is within reach.
double start_height(const DepositedSpheres &packing, double x, double y, double r)
{
  const double reach = r + packing.r_max;
  const double top = packing.grid.highest_top(x - reach, x + reach, y - reach, y + reach);
  return std::max(packing.domain.z_floor + r, top + r);
}

// Vertical fall from p: distance to the first contact (sphere or floor), and which.
double fall_event(const DepositedSpheres &packing, Vec3 p, double r,
                  const std::vector<Constraint> &active, Constraint &hit, bool &entering_now)
{
  const LayeredGrid &grid = packing.grid;
  const double z_floor = packing.domain.z_floor;
  entering_now = false;
  double best = p.z - (z_floor + r);
  hit = Constraint{false, kFloorPlane, 0, 0, {0, 0, 1}, z_floor + r};
  const double reach = r + packing.r_max;
  const double grazing_depth = kDepositionGrazingDepth * 2.0 * r;
  // Layers from the top down; stop when a layer cannot hold a closer contact.
  for (int iz = std::min(grid.layers() - 1, grid.layer_of(p.z + reach)); iz >= 0; --iz) {
    const double layer_top = grid.floor_z() + (iz + 1) * grid.layer_width();
    if (p.z - layer_top - reach > best) break;
    grid.visit(p.x - reach, p.x + reach, p.y - reach, p.y + reach, iz, iz,
               [&](std::int32_t i, double sx, double sy, int ix, int iy) {
                 const Constraint k{true, i, ix, iy, packing.centre_of(i) + Vec3{sx, sy, 0.0},
                                    r + packing.radii[i]};
                 for (const auto &a : active)
                   if (a.same(k)) return;
                 const Vec3 delta = p - k.c;
                 if (delta.z <= 0.0) return;  // centre not below p: the fall moves away
                 const double h2 = delta.x * delta.x + delta.y * delta.y;
                 const double D2 = k.dist * k.dist;
                 if (h2 >= D2) return;
                 // Deepest point of the fall (beside the centre) barely inside: grazing.
                 if (h2 - D2 > -2.0 * k.dist * grazing_depth) return;
                 const double s = std::sqrt(D2 - h2);
                 const double t1 = delta.z - s;  // overlap for t in (t1, delta.z + s)
                 double t = t1;
                 bool now = false;
                 if (t1 < 0.0) {
                   t = 0.0;
                   now = true;
                 }
                 if (t < best) {
                   best = t;
                   hit = k;
                   entering_now = now;
                 }
               });
  }
  return best;
}

// Roll along circle `path` (constraints `active` kept): the first event parameter; `hit` is
// the constraint entered, if the event is a new contact.
double roll_event(const DepositedSpheres &packing, const Circle &path, double r,
                  const std::vector<Constraint> &active, const ForceLaw *forces, int n_forces,
                  Constraint &hit, bool &is_contact, bool &entering_now)
{
  const LayeredGrid &grid = packing.grid;
  double best = path.t_end;
  is_contact = false;
  entering_now = false;
  // Support forces reaching zero: the sphere leaves that support.
  for (int a = 0; a < n_forces; ++a) {
    bool now;
    const double t = first_entry(forces[a].K, forces[a].P, forces[a].Q, best, now);
    if (!now && t < best) best = t;
  }
  auto take = [&](const Constraint &k, double t, bool now) {
    if (t < best || (now && !entering_now)) {
      best = std::min(best, t);
      hit = k;
      is_contact = true;
      entering_now = now;
    }
  };
  auto consider = [&](const Constraint &k, double K, double P, double Q) {
    bool now;
    const double t = first_entry(K, P, Q, best, now);
    take(k, t, now);
  };
  // Planes: f / rho = (n.m - offset) / rho + n.e1 cos t + n.e2 sin t.
  packing.for_each_plane(r, [&](const Constraint &k) {
    for (const auto &a : active)
      if (a.same(k)) return;
    consider(k, (dot(k.c, path.m) - k.dist) / path.rho, dot(k.c, path.e1), dot(k.c, path.e2));
  });
  if (packing.domain.has_cylinder) {
    const Constraint wall = packing.cylinder_wall(r);
    bool wall_active = false;
    for (const auto &a : active) wall_active = wall_active || a.same(wall);
    if (!wall_active) {
      bool now;
      const double t = circle_wall_entry(path, wall, r, best, now);
      take(wall, t, now);
    }
  }
  // Spheres: (|p - c|^2 - D^2) / (2 rho D) = K + P cos t + Q sin t.
  const Vec3 axis = cross(path.e1, path.e2);
  const double reach = r + packing.r_max;
  const double ex = path.rho * std::sqrt(std::max(0.0, 1.0 - axis.x * axis.x)) + reach;
  const double ey = path.rho * std::sqrt(std::max(0.0, 1.0 - axis.y * axis.y)) + reach;
  const double ez = path.rho * std::sqrt(std::max(0.0, 1.0 - axis.z * axis.z)) + reach;
  grid.visit(path.m.x - ex, path.m.x + ex, path.m.y - ey, path.m.y + ey,
             grid.layer_of(path.m.z - ez), grid.layer_of(path.m.z + ez),
             [&](std::int32_t i, double sx, double sy, int ix, int iy) {
               const Constraint k{true, i, ix, iy, packing.centre_of(i) + Vec3{sx, sy, 0.0},
                                  r + packing.radii[i]};
               const Vec3 delta = path.m - k.c;
               const double d2 = dot(delta, delta);
               const double far = path.rho + k.dist;
               if (d2 >= far * far) return;  // the circle never comes within reach
               for (const auto &a : active)
                 if (a.same(k)) return;
               const double scale = 1.0 / (2.0 * path.rho * k.dist);
               consider(k, (d2 + path.rho * path.rho - k.dist * k.dist) * scale,
                        2.0 * path.rho * dot(path.e1, delta) * scale,
                        2.0 * path.rho * dot(path.e2, delta) * scale);
             });
  return best;
}

// ---------------------------------------------------------------------------------------------
// The roll of one segment.

namespace {

// Lowest point of the circle, measured from t = 0 (the path descends from there).
double lowest_point(const Circle &c)
{
  return wrap_angle(std::atan2(c.e2.z, c.e1.z) + kPi);
}

// A way off the top of a sphere (contact normal `up`) that enters no touching constraint, when
// random directions found none: the ways left free form a cone in the tangent plane, an
// intersection of half-planes (one per touching constraint); when it is not empty one of its
// edges is the edge of some half-plane, so the edges of every half-plane are the candidates,
// and one free candidate is drawn. A cone of measure zero (a slot one diameter wide: only along
// its walls) is found this way; false when every way is blocked (the sphere is wedged).
bool free_way_off_top(Vec3 up, const ContactSet &contacts, const Descent &descent,
                      EquilibriumDraws &draws, Vec3 &way)
{
  std::vector<Vec3> free_ways;
  for (const Vec3 &n : contacts.normals) {
    const Vec3 across = n - dot(n, up) * up;  // the half-plane's inward normal in the plane
    if (!(norm(across) > defaults::kDepositionZeroLength)) continue;
    const Vec3 edge = unit(cross(up, across));
    for (const Vec3 candidate : {edge, -1.0 * edge, unit(across)})
      if (!blocked(candidate, contacts, descent)) free_ways.push_back(candidate);
  }
  if (free_ways.empty()) return false;
  const auto pick = static_cast<std::size_t>(draws.uniform() * free_ways.size());
  way = free_ways[std::min(pick, free_ways.size() - 1)];
  return true;
}

}  // namespace

// The roll for the active set (one or two constraints, at least one sphere), and the laws of
// the support forces along it. At an unstable equilibrium (on top of a sphere, or on the
// ridge of two supports) the roll starts in a random direction (from `draws`) that enters no
// touching constraint; when every way off a top, or both ways along a ridge, are blocked the
// sphere is wedged (at rest).
RollSetup make_roll(Vec3 p, const ContactSet &contacts, const Descent &descent, bool equilibrium,
                    EquilibriumDraws &draws, Circle &path, ForceLaw *forces)
{
  const int n_act = descent.n_active;
  const Constraint *act[2] = {&contacts.constraints[descent.active[0]],
                              n_act > 1 ? &contacts.constraints[descent.active[1]] : nullptr};
  if (n_act == 1) {  // great circle in the vertical plane through the contact normal
    const Constraint &j = *act[0];
    path.m = j.c;
    path.rho = norm(p - j.c);
    path.e1 = (1.0 / path.rho) * (p - j.c);
    Vec3 dir = descent.d;
    if (equilibrium) {
      bool free = false;
      for (int attempt = 0; attempt < defaults::kDepositionLeaveAttempts && !free; ++attempt) {
        const Vec3 u = draws.horizontal_direction();
        dir = u - dot(u, path.e1) * path.e1;
        free = !blocked(dir, contacts, descent);
      }
      if (!free && !free_way_off_top(path.e1, contacts, descent, draws, dir))
        return RollSetup::Wedged;
    }
    dir = dir - dot(dir, path.e1) * path.e1;
    if (!(norm(dir) > defaults::kDepositionZeroLength)) return RollSetup::Degenerate;
    path.e2 = unit(dir);
    // mu(t) = n_z(t): the normal force vanishes at the sphere's equator.
    forces[0] = {0.0, path.e1.z, path.e2.z};
  } else {
    const Constraint &a = *act[0], &b = *act[1];
    const Vec3 axis = (a.is_sphere && b.is_sphere) ? unit(b.c - a.c) : (a.is_sphere ? b.c : a.c);
    const Constraint &s = a.is_sphere ? a : b;  // a sphere of the pair fixes the circle centre
    path.m = s.c + dot(p - s.c, axis) * axis;
    const Vec3 radial = p - path.m;
    path.rho = norm(radial);
    if (!(path.rho > 0.0)) return RollSetup::Degenerate;
    path.e1 = (1.0 / path.rho) * radial;
    path.e2 = unit(cross(axis, path.e1));
    if (equilibrium) {
      if (draws.sign()) path.e2 = -1.0 * path.e2;
      if (blocked(path.e2, contacts, descent)) path.e2 = -1.0 * path.e2;
      if (blocked(path.e2, contacts, descent)) return RollSetup::Wedged;
    } else if (dot(path.e2, descent.d) < 0.0) {
      path.e2 = -1.0 * path.e2;
    }
    // Normals in the (axis, radial) basis: sphere (sigma, tau) = ((m - c).axis, rho) / |p - c|,
    // plane (n.axis, 0). Forces: solve sigma_a mu_a + sigma_b mu_b = axis_z,
    // tau_a mu_a + tau_b mu_b = radial_z(t) (balance of -g = e_z in that plane).
    double sigma[2], tau[2];
    for (int q = 0; q < 2; ++q) {
      const Constraint &k = *act[q];
      if (k.is_sphere) {
        const double dist = norm(p - k.c);
        sigma[q] = dot(path.m - k.c, axis) / dist;
        tau[q] = path.rho / dist;
      } else {
        sigma[q] = dot(k.c, axis);
        tau[q] = 0.0;
      }
    }
    const double det = sigma[0] * tau[1] - sigma[1] * tau[0];
    if (std::fabs(det) < defaults::kDepositionSingularRoll) return RollSetup::Degenerate;
    const double nz = axis.z;
    forces[0] = {nz * tau[1] / det, -sigma[1] * path.e1.z / det, -sigma[1] * path.e2.z / det};
    forces[1] = {-tau[0] * nz / det, sigma[0] * path.e1.z / det, sigma[0] * path.e2.z / det};
  }
  path.t_end = lowest_point(path);
  return RollSetup::Ok;
}

}  // namespace deposition_detail
}  // namespace tapmc
