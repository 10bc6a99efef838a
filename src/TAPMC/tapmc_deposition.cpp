// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Sequential deposition with steepest descent (Jullien & Meakin 1987): paths, contacts, grid.
//
// A dropped sphere (centre p, radius r) moves by steepest descent of its height under the
// non-penetration constraints of the spheres and planes it touches. Constraint k keeps
// f_k(p) >= 0 (sphere: |p - c_k| >= r + r_k; plane: n_k.p >= offset_k) with outward unit normal
// n_k. At a point, the descent direction d is the projection of gravity g = -e_z onto the cone
// {d : n_k.d >= 0 for every touching k}; the active set S (at most three independent normals)
// satisfies g + sum_S mu_k n_k = d with support forces mu_k >= 0 (the KKT conditions). Then:
//   S empty (or vertical walls only) -> vertical fall (a line),
//   S = {one sphere}                 -> roll on the great circle in the vertical plane,
//   S = {sphere, sphere or wall}     -> roll on the circle of points touching both,
//   d = 0, floor in S or |S| = 3     -> at rest (mu >= 0: gravity is balanced; for three spheres
//                                       this is the projection of p inside their triangle).
// Every path is a line or a circle p(t) = m + rho (cos t e1 + sin t e2); along a circle each
// contact function and each support force is K + P cos t + Q sin t, so the next event (a new
// contact, a support force reaching zero, the lowest point) is found in closed form.
//
// A vertical cylindrical container (axis A, radius R_c) adds the constraint
// |p_xy - A| <= R_c - r, with the horizontal normal -(p_xy - A) / |p_xy - A|. Along a circle
// its contact function is quadratic in (cos t, sin t) (a trigonometric polynomial of degree 2),
// and so is every contact function along the one new path, the roll on one sphere j along the
// wall: with the azimuth psi(t) = psi0 + t about the axis, p_xy = A + rho u(psi) and
// p_z = z_j + Z, Z^2 = D_j^2 - |p_xy - c_j,xy|^2 is K + P cos t + Q sin t, and the contact
// function of a sphere k, L(t) + 2 (z_j - z_k) Z with L of degree 1, vanishes only where
// L^2 - 4 (z_j - z_k)^2 Z^2 (degree 2) does. The roots of a degree-2 polynomial (at most 4 a
// turn) come from a quartic in tan(u / 2) on each quarter turn; they split the path into pieces
// on which a contact function keeps its sign, sampled on the true function (not the squared
// one), and the entry found is refined by bisection on the true function. On that path the
// support of j vanishes at the height of c_j (Z = 0, in closed form), the wall's never vanishes
// (it grows as the sphere moves away from j), and the lowest point, where the sphere, the axis
// and c_j lie in one vertical plane with c_j beyond the axis, is a true rest on two supports.
//
// In this file, in order: the descent at a point (from the touching constraints alone); the
// searches of the deposited spheres (contacts, start of a drop, next event of a fall or a roll);
// the roll of one segment; the roll along the cylinder wall; and the engine (Impl) that drops a
// sphere with them. The shared types are in tapmc_deposition_detail.h, the layered grid and the
// deposited spheres in tapmc_deposition_grid.h, the root finding in tapmc_deposition_roots.h/.cpp.
#include "tapmc_deposition.h"

#include "tapmc_checks.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_deposition_grid.h"
#include "tapmc_deposition_roots.h"
#include "tapmc_math.h"
#include "tapmc_random.h"
#include "tapmc_stereology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {

// The internals shared by the deposition's files (tapmc_deposition_detail.h).
using namespace deposition_detail;

namespace {

// ---------------------------------------------------------------------------------------------
// The descent at a point (the KKT conditions of the header comment), from the contacts alone.

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

// Where a circle first enters the cylinder wall (t <= t_max, or +inf; `now` as first_entry):
// (R_c - r)^2 - |m_xy - A + rho (cos t e1_xy + sin t e2_xy)|^2 is of degree 2 in (cos t, sin t).
double circle_wall_entry(const Circle &path, const Constraint &wall, double r, double t_max,
                         bool &now)
{
  now = false;
  const double vx = path.m.x - wall.c.x, vy = path.m.y - wall.c.y;
  const double ax = path.rho * path.e1.x, ay = path.rho * path.e1.y;
  const double bx = path.rho * path.e2.x, by = path.rho * path.e2.y;
  const double aa = ax * ax + ay * ay, bb = bx * bx + by * by, ab = ax * bx + ay * by;
  const Trig2 f{wall.dist * wall.dist - (vx * vx + vy * vy) - 0.5 * (aa + bb),
                -2.0 * (vx * ax + vy * ay), -2.0 * (vx * bx + vy * by), -0.5 * (aa - bb), -ab};
  const double grazing = kDepositionGrazingDepth * 2.0 * r;
  // f is about 2 (R_c - r) times the gap: never deeper than the grazing depth, never entered
  if (f.lower_bound() > -grazing * 2.0 * wall.dist) return kInf;
  double breaks[16];
  const int n = trig2_sign_changes(f, t_max, breaks);
  return first_entry_scan([&](double t) { return gap_of(wall, path.at(t)); }, breaks, n, t_max,
                          grazing, kDepositionSupportTolerance * 2.0 * r, now);
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

// Lowest point of the circle, measured from t = 0 (the path descends from there).
double lowest_point(const Circle &c)
{
  return wrap_angle(std::atan2(c.e2.z, c.e1.z) + kPi);
}


// The roll for the active set (one or two constraints, at least one sphere), and the laws of
// the support forces along it. At an unstable equilibrium (on top of a sphere, or on the
// ridge of two supports) the roll starts in a random direction (from `draws`) that enters no
// touching constraint; when both ways along a ridge are blocked the sphere is wedged (at rest).
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
      if (!free) return RollSetup::Degenerate;
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


// At an equilibrium on sphere j and the wall (the sphere, the wall's normal and the vertical in
// one plane): a rest when the sphere lies on the far side of the axis from c_j (the lowest point
// of the path: it rises both ways), or when c_j is on the axis (the path is level); on the near
// side it is the highest point, left in a random direction.
bool wall_pair_rests(Vec3 p, const Constraint &j, const Constraint &wall)
{
  return (p.x - wall.c.x) * (j.c.x - wall.c.x) + (p.y - wall.c.y) * (j.c.y - wall.c.y) <= 0.0;
}

RollSetup make_wall_roll(Vec3 p, const Constraint &j, const Constraint &wall,
                         const ContactSet &contacts, const Descent &descent, bool equilibrium,
                         EquilibriumDraws &draws, WallRoll &path)
{
  path.axis = {wall.c.x, wall.c.y, 0.0};
  const double hx = p.x - wall.c.x, hy = p.y - wall.c.y;
  path.rho = std::hypot(hx, hy);
  // the support of j holds only from above its centre (KKT: mu_j = n_j,z / (1 - (n_j.n_w)^2))
  if (!(path.rho > 0.0) || !(p.z > j.c.z)) return RollSetup::Degenerate;
  path.u0 = {hx / path.rho, hy / path.rho, 0.0};
  Vec3 v{-path.u0.y, path.u0.x, 0.0};
  if (equilibrium) {  // the highest point: the path is level there, both ways descend
    if (draws.sign()) v = -1.0 * v;
    if (blocked(v, contacts, descent)) v = -1.0 * v;
    if (blocked(v, contacts, descent)) return RollSetup::Wedged;
  } else if (dot(v, descent.d) < 0.0) {
    v = -1.0 * v;
  }
  path.v0 = v;
  path.cj = j.c;
  const Vec3 q = path.xy(0.0);
  const double dx = q.x - j.c.x, dy = q.y - j.c.y, dz = p.z - j.c.z;
  path.D2 = dx * dx + dy * dy + dz * dz;
  const double wx = path.axis.x - j.c.x, wy = path.axis.y - j.c.y;
  path.hK = wx * wx + wy * wy + path.rho * path.rho;
  path.hP = 2.0 * path.rho * (wx * path.u0.x + wy * path.u0.y);
  path.hQ = 2.0 * path.rho * (wx * path.v0.x + wy * path.v0.y);
  path.t_end = wrap_angle(std::atan2(path.hQ, path.hP));
  // h2 already at its largest (a rounding-level negative slope): no way down
  if (path.t_end > kPi) path.t_end = path.hP > 0.0 ? 0.0 : kPi;
  return RollSetup::Ok;
}

// The first event of a wall roll: a new contact (`hit`, `is_contact`, `entering_now` as in
// roll_event), the support of j lost where the centre reaches the height of c_j (`support_lost`),
// or the lowest point.
double wall_roll_event(const DepositedSpheres &packing, const WallRoll &path, double r,
                       const std::vector<Constraint> &active, Constraint &hit, bool &is_contact,
                       bool &entering_now, bool &support_lost)
{
  double best = path.t_end;
  is_contact = false;
  entering_now = false;
  support_lost = false;
  const double D = std::sqrt(path.D2);
  const double scale = 1.0 / (2.0 * path.rho * D);
  // Z^2 = D^2 - h2 reaching zero
  {
    bool now;
    const double t = first_entry((path.D2 - path.hK) * scale, -path.hP * scale,
                                 -path.hQ * scale, best, now);
    if (!now && t < best) {
      best = t;
      support_lost = true;
    }
  }
  auto take = [&](const Constraint &k, double t, bool now) {
    if (t < best || (now && !entering_now)) {
      best = std::min(best, t);
      hit = k;
      is_contact = true;
      entering_now = now;
      support_lost = false;
    }
  };
  // The floor, only below c_j's height z_j: Z^2 - (z_floor + r - z_j)^2 reaching zero.
  const double H = packing.domain.z_floor + r - path.cj.z;
  if (H > 0.0) {
    bool now;
    const double t = first_entry((path.D2 - H * H - path.hK) * scale, -path.hP * scale,
                                 -path.hQ * scale, best, now);
    take(Constraint{false, kFloorPlane, 0, 0, {0, 0, 1}, packing.domain.z_floor + r}, t, now);
  }
  // Spheres k: |p - c_k|^2 - D_k^2 = L(t) + 2 (z_j - z_k) Z(t), L = H_k + (z_j - z_k)^2 + Z^2
  // - D_k^2 with H_k = |p_xy - c_k,xy|^2, both of degree 1; it vanishes only where
  // L^2 - 4 (z_j - z_k)^2 Z^2 does. The path stays within D of c_j.
  const LayeredGrid &grid = packing.grid;
  const double reach = D + r + packing.r_max;
  const double grazing = kDepositionGrazingDepth * 2.0 * r;
  const double z_start = path.at(0.0).z;
  grid.visit(path.cj.x - reach, path.cj.x + reach, path.cj.y - reach, path.cj.y + reach,
             grid.layer_of(path.cj.z - reach), grid.layer_of(path.cj.z + reach),
             [&](std::int32_t i, double, double, int, int) {
               const Constraint k{true, i, 0, 0, packing.centre_of(i), r + packing.radii[i]};
               const Vec3 jk = k.c - path.cj;
               if (dot(jk, jk) >= (D + k.dist) * (D + k.dist)) return;
               const double wx = path.axis.x - k.c.x, wy = path.axis.y - k.c.y;
               const double s_k = std::hypot(wx, wy);
               if (std::fabs(s_k - path.rho) >= k.dist) return;  // never within D_k of the path
               for (const auto &a : active)
                 if (a.same(k)) return;
               const double delta = path.cj.z - k.c.z;
               const double lK = wx * wx + wy * wy + path.rho * path.rho + delta * delta +
                                 path.D2 - path.hK - k.dist * k.dist;
               const double lP = 2.0 * path.rho * (wx * path.u0.x + wy * path.u0.y) - path.hP;
               const double lQ = 2.0 * path.rho * (wx * path.v0.x + wy * path.v0.y) - path.hQ;
               // lower bound of L + 2 delta Z with 0 <= Z <= Z(0)
               const double low = lK - std::hypot(lP, lQ) +
                                  std::min(0.0, 2.0 * delta * (z_start - path.cj.z));
               if (low > -grazing * 2.0 * k.dist) return;
               Trig2 f = Trig2::square(lK, lP, lQ);
               const double d4 = 4.0 * delta * delta;
               f.a0 -= d4 * (path.D2 - path.hK);
               f.a1 += d4 * path.hP;
               f.b1 += d4 * path.hQ;
               double breaks[32];
               int n = trig2_sign_changes(f, best, breaks);
               n += trig2_sign_changes(Trig2{lK, lP, lQ, 0.0, 0.0}, best, breaks + n);
               bool now;
               const double t = first_entry_scan(
                   [&](double u) { return norm(path.at(u) - k.c) - k.dist; }, breaks, n, best,
                   grazing, kDepositionSupportTolerance * k.dist, now);
               take(k, t, now);
             });
  return best;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The engine: the deposited spheres, the equilibrium draws of the sphere being dropped, the
// counters, and the drop itself (segment after segment: contacts, descent, fall or roll).
struct SequentialDeposition::Impl {
  DepositedSpheres packing;
  EquilibriumDraws equilibrium_draws;  // of sphere packing.size(), the next to be inserted
  DepositionStats stats;

  void insert(Vec3 p, double r)
  {
    packing.insert(p, r);
    equilibrium_draws.start_sphere(packing.size());
  }

  // One attempt: fall and roll from (x, y) until at rest, or until the segment cap.
  DropOutcome descend(double x, double y, double r)
  {
    Vec3 p{x, y, 0.0};
    packing.wrap(p);
    p.z = start_height(packing, p.x, p.y, r);
    std::vector<Constraint> forced;
    std::vector<int> forced_idx;
    std::vector<Constraint> active;
    ContactSet contacts;  // storage reused by every segment of this drop
    for (int segment = 0; segment < kDepositionMaxSegments; ++segment) {
      ++stats.segments;
      collect_touching(packing, p, r, contacts);
      forced_idx.clear();
      for (const auto &f : forced)
        for (int k = 0; k < contacts.size(); ++k)
          if (contacts.constraints[k].same(f)) forced_idx.push_back(k);
      Descent descent = solve_descent(contacts, forced_idx);
      if (!descent.found && !forced_idx.empty()) {
        forced.clear();
        forced_idx.clear();
        descent = solve_descent(contacts, forced_idx);
      }
      if (!descent.found) break;  // no consistent active set: give up this attempt

      active.clear();
      bool on_floor = false;
      int n_spheres = 0;
      const Constraint *wall = nullptr, *sphere = nullptr;
      for (int a = 0; a < descent.n_active; ++a) {
        const Constraint &k = contacts.constraints[descent.active[a]];
        active.push_back(k);
        on_floor = on_floor || (!k.is_sphere && k.id == kFloorPlane);
        n_spheres += k.is_sphere ? 1 : 0;
        if (k.is_cylinder) wall = &k;
        if (k.is_sphere) sphere = &k;
      }
      // on one sphere along the cylinder wall (the only active pair that is not a circle)
      const bool wall_pair = wall != nullptr && n_spheres == 1 && descent.n_active == 2;
      const bool equilibrium = norm(descent.d) < kDepositionEquilibriumTolerance;
      if (equilibrium &&
          (on_floor || descent.n_active == 3 || (wall_pair && wall_pair_rests(p, *sphere, *wall))))
        return {p.x, p.y, p.z, on_floor ? RestingOn::Floor : RestingOn::Supports, segment + 1};
      if (equilibrium) ++stats.perturbations;

      Constraint hit{};
      bool entering_now = false;
      if (n_spheres == 0) {  // free fall (possibly sliding along vertical walls)
        const double t = fall_event(packing, p, r, active, hit, entering_now);
        p.z -= t;
        if (!(t > 0.0) && entering_now) {
          forced.push_back(hit);
        } else {
          forced.clear();
        }
        continue;
      }
      if (wall_pair) {
        ++stats.wall_rolls;
        WallRoll path;
        const RollSetup setup = make_wall_roll(p, *sphere, *wall, contacts, descent, equilibrium,
                                               equilibrium_draws, path);
        if (setup == RollSetup::Wedged) return {p.x, p.y, p.z, RestingOn::Supports, segment + 1};
        if (setup == RollSetup::Degenerate) break;
        bool is_contact = false, support_lost = false;
        const double t = wall_roll_event(packing, path, r, active, hit, is_contact, entering_now,
                                         support_lost);
        if (is_contact && entering_now) {
          bool known = false;
          for (const auto &f : forced) known = known || f.same(hit);
          if (!known) forced.push_back(hit);
          continue;
        }
        forced.clear();
        p = path.at(t);
        // Heights set exactly where the event fixes them: level with c_j (its support is lost;
        // the next segment falls clear of it) or on the floor.
        if (support_lost) p.z = path.cj.z;
        if (is_contact && !hit.is_sphere) p.z = packing.domain.z_floor + r;
        continue;
      }
      // Roll on one sphere, or on two constraints with at least one sphere.
      Circle path;
      ForceLaw forces[2];
      const RollSetup setup =
          make_roll(p, contacts, descent, equilibrium, equilibrium_draws, path, forces);
      if (setup == RollSetup::Wedged) return {p.x, p.y, p.z, RestingOn::Supports, segment + 1};
      if (setup == RollSetup::Degenerate) break;
      bool is_contact = false;
      const double t = roll_event(packing, path, r, active, forces, descent.n_active, hit,
                                  is_contact, entering_now);
      if (is_contact && entering_now) {
        bool known = false;
        for (const auto &f : forced) known = known || f.same(hit);
        if (!known) forced.push_back(hit);
        continue;  // same point, the entered constraint joins the active set
      }
      forced.clear();
      p = path.at(t);
      packing.wrap(p);
    }
    return {p.x, p.y, p.z, RestingOn::Unresolved, kDepositionMaxSegments};
  }
};

namespace {
void check_radius(double radius, double max_radius)
{
  if (!(radius > 0.0) || radius > max_radius)
    throw_outside_range("radius", radius, "(0, max_radius] = (0, " + number(max_radius) + "]");
}

// A tube needs walls in x and y, room for the largest sphere, and its disk inside the box (the
// box bounds the search grid).
void check_cylinder(const DepositionDomain &domain, double max_radius)
{
  const char *why = "{false} (a cylindrical container needs walls in x and y)";
  if (domain.periodic_x)
    throw std::invalid_argument(outside_range_message("periodic_x", "true", why));
  if (domain.periodic_y)
    throw std::invalid_argument(outside_range_message("periodic_y", "true", why));
  const Cylinder &c = domain.cylinder;
  validate(c, max_radius);
  const double half = 0.5 * std::min(domain.xhi - domain.xlo, domain.yhi - domain.ylo);
  if (!(c.radius <= half))
    throw_outside_range("cylinder radius", c.radius,
                        "(max_radius, min(xhi - xlo, yhi - ylo) / 2] = (" + number(max_radius) +
                            ", " + number(half) + "] (the disk must lie inside the box)");
  if (!(c.cx >= domain.xlo + c.radius && c.cx <= domain.xhi - c.radius))
    throw_outside_range("cylinder cx", c.cx,
                        "[xlo + radius, xhi - radius] = [" + number(domain.xlo + c.radius) +
                            ", " + number(domain.xhi - c.radius) +
                            "] (the disk must lie inside the box)");
  if (!(c.cy >= domain.ylo + c.radius && c.cy <= domain.yhi - c.radius))
    throw_outside_range("cylinder cy", c.cy,
                        "[ylo + radius, yhi - radius] = [" + number(domain.ylo + c.radius) +
                            ", " + number(domain.yhi - c.radius) +
                            "] (the disk must lie inside the box)");
}
}  // namespace

SequentialDeposition::SequentialDeposition(const DepositionDomain &domain, double max_radius,
                                           std::uint64_t seed)
    : impl_(std::make_unique<Impl>())
{
  if (!(max_radius > 0.0) || !std::isfinite(max_radius))
    throw_outside_range("max_radius", max_radius, "(0, +inf)");
  const double diameter = 2.0 * max_radius;
  const std::string one_diameter = "[2 max_radius, +inf) = [" + number(diameter) + ", +inf)";
  if (!(domain.xhi - domain.xlo >= diameter))
    throw_outside_range("x extent xhi - xlo", domain.xhi - domain.xlo, one_diameter);
  if (!(domain.yhi - domain.ylo >= diameter))
    throw_outside_range("y extent yhi - ylo", domain.yhi - domain.ylo, one_diameter);
  if (!std::isfinite(domain.z_floor)) throw_outside_range("z_floor", domain.z_floor, "(finite)");
  if (domain.has_cylinder) check_cylinder(domain, max_radius);
  DepositedSpheres &packing = impl_->packing;
  packing.domain = domain;
  packing.r_max = max_radius;
  // Cells of one maximal contact distance (2 r_max): a fall visits 3 x 3 columns.
  packing.grid.setup(domain, diameter);
  impl_->equilibrium_draws = EquilibriumDraws(seed);
}

SequentialDeposition::~SequentialDeposition() = default;
SequentialDeposition::SequentialDeposition(SequentialDeposition &&) noexcept = default;
SequentialDeposition &SequentialDeposition::operator=(SequentialDeposition &&) noexcept = default;

void SequentialDeposition::add_fixed_sphere(double x, double y, double z, double radius)
{
  check_radius(radius, impl_->packing.r_max);
  Vec3 p{x, y, z};
  impl_->packing.wrap(p);
  impl_->insert(p, radius);
}

DropOutcome SequentialDeposition::drop(double x, double y, double radius)
{
  Impl &s = *impl_;
  const DepositionDomain &domain = s.packing.domain;
  check_radius(radius, s.packing.r_max);
  const double slack = kDepositionSupportTolerance * radius;
  if (domain.has_cylinder) {
    const Cylinder &c = domain.cylinder;
    const double h = std::hypot(x - c.cx, y - c.cy);
    if (!(h <= c.radius - radius + slack))
      throw_outside_range("drop point distance from the cylinder axis", h,
                          "[0, cylinder radius - r] = [0, " + number(c.radius - radius) + "]");
  }
  if (!domain.periodic_x && (x < domain.xlo + radius - slack || x > domain.xhi - radius + slack))
    throw_outside_range("drop point x", x,
                        "[xlo + r, xhi - r] = [" + number(domain.xlo + radius) + ", " +
                            number(domain.xhi - radius) + "] (between walls)");
  if (!domain.periodic_y && (y < domain.ylo + radius - slack || y > domain.yhi - radius + slack))
    throw_outside_range("drop point y", y,
                        "[ylo + r, yhi - r] = [" + number(domain.ylo + radius) + ", " +
                            number(domain.yhi - radius) + "] (between walls)");
  DropOutcome out = s.descend(x, y, radius);
  if (out.rest != RestingOn::Unresolved) s.insert({out.x, out.y, out.z}, radius);
  return out;
}

std::size_t SequentialDeposition::size() const { return impl_->packing.size(); }
const double *SequentialDeposition::centre(std::size_t i) const
{
  return &impl_->packing.centres[3 * i];
}
double SequentialDeposition::radius(std::size_t i) const { return impl_->packing.radii[i]; }
const DepositionStats &SequentialDeposition::stats() const { return impl_->stats; }

// ---------------------------------------------------------------------------------------------
void validate(const PackingParams &params)
{
  if (params.n < 1 || params.n > std::numeric_limits<std::int32_t>::max() - 1)
    throw_outside_range("N", params.n, "[1, 2^31 - 2] (a number of spheres)");
  if (!(params.radius > 0.0) || !std::isfinite(params.radius))
    throw_outside_range("R", params.radius, "(0, +inf) (the mean sphere radius)");
  if (!(params.dispersity >= 0.0 && params.dispersity < 1.0))
    throw_outside_range("dispersity", params.dispersity,
                        "[0, 1) (radii uniform in [R(1 - W), R(1 + W)])");
  if (!(params.density > 0.0)) throw_outside_range("density", params.density, "(0, +inf)");
}

Packing deposit_packing(std::int64_t n, const RadiusDistribution &radii,
                        const DepositionDomain &domain, std::uint64_t seed)
{
  if (n < 0 || n > std::numeric_limits<std::int32_t>::max() - 1)
    throw_outside_range("n", n, "[0, 2^31 - 2]");
  if (!(radii.r_min > 0.0)) throw_outside_range("r_min", radii.r_min, "(0, +inf)");
  if (!(radii.r_max >= radii.r_min && std::isfinite(radii.r_max)))
    throw_outside_range("r_max", radii.r_max,
                        "[r_min, +inf) = [" + number(radii.r_min) + ", +inf)");
  SequentialDeposition engine(domain, radii.r_max, seed);
  Packing out;
  out.xyz.reserve(3 * static_cast<std::size_t>(n));
  out.radius.reserve(static_cast<std::size_t>(n));
  const double top_slack = kDepositionSupportTolerance * 2.0 * radii.r_max;
  std::int64_t redrops = 0, unresolved = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    // Sphere i's draws: its radius at position 0, the drop point of attempt a at position 1 + a.
    const CounterRandom draws(seed, RandomPurpose::kDepositionDrops, static_cast<std::uint64_t>(i));
    const double r = radii.is_monodisperse()
                         ? radii.r_min
                         : radii.r_min + (radii.r_max - radii.r_min) * draws.uniform(0);
    // Drop points: uniform over the box (periodic) or over [lo + r, hi - r] (walls).
    const double x_lo = domain.periodic_x ? domain.xlo : domain.xlo + r;
    const double x_span = domain.periodic_x ? domain.xhi - domain.xlo : domain.xhi - domain.xlo - 2.0 * r;
    const double y_lo = domain.periodic_y ? domain.ylo : domain.ylo + r;
    const double y_span = domain.periodic_y ? domain.yhi - domain.ylo : domain.yhi - domain.ylo - 2.0 * r;
    DropOutcome o{};
    for (int attempt = 0; attempt < defaults::kDepositionMaxAttempts; ++attempt) {
      const RandomBlock point = draws.block(1 + static_cast<std::uint64_t>(attempt));
      const double u = uniform_from_u64(join_u32(point[0], point[1]));
      const double v = uniform_from_u64(join_u32(point[2], point[3]));
      double x = x_lo + x_span * u, y = y_lo + y_span * v;
      if (domain.has_cylinder) {  // uniform on the disk of radius R_c - r about the axis
        const Cylinder &c = domain.cylinder;
        const double h = (c.radius - r) * std::sqrt(u), angle = kTwoPi * v;
        x = c.cx + h * std::cos(angle);
        y = c.cy + h * std::sin(angle);
      }
      o = engine.drop(x, y, r);
      if (o.rest != RestingOn::Unresolved) break;
      ++redrops;
    }
    if (o.rest == RestingOn::Unresolved) {
      engine.add_fixed_sphere(o.x, o.y, o.z, r);
      ++unresolved;
    }
    if (o.z + r > domain.z_top + top_slack)
      throw std::runtime_error("sphere " + std::to_string(i) + " of " + std::to_string(n) +
                               " rests with its top at z = " + number(o.z + r) +
                               ", above the top limit z_top = " + number(domain.z_top) +
                               ": the domain cannot hold the spheres");
    out.xyz.insert(out.xyz.end(), {o.x, o.y, o.z});
    out.radius.push_back(r);
  }
  out.stats = engine.stats();
  out.stats.redrops = redrops;
  out.stats.unresolved = unresolved;
  return out;
}

std::vector<std::uint8_t> cylinder_wall_contacts(const Packing &packing,
                                                 const DepositionDomain &domain)
{
  const std::size_t n = packing.radius.size();
  std::vector<std::uint8_t> out(n, 0);
  if (!domain.has_cylinder) return out;
  const Cylinder &c = domain.cylinder;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = packing.radius[i];
    const double h = std::hypot(packing.xyz[3 * i] - c.cx, packing.xyz[3 * i + 1] - c.cy);
    out[i] = (c.radius - r) - h <= kDepositionSupportTolerance * 2.0 * r ? 1 : 0;
  }
  return out;
}

void bulk_window(const Packing &packing, const DepositionDomain &domain, double margin,
                 double &z0, double &z1)
{
  double mean = 0.0;
  const std::size_t n = packing.radius.size();
  for (std::size_t i = 0; i < n; ++i) mean += packing.xyz[3 * i + 2] - domain.z_floor;
  mean = n ? mean / static_cast<double>(n) : 0.0;
  z0 = domain.z_floor + margin;
  z1 = domain.z_floor + 2.0 * mean - margin;
}

double slab_volume_fraction(const Packing &packing, const DepositionDomain &domain, double z0,
                            double z1)
{
  const stereo::Spheres spheres{packing.xyz.data(), packing.radius.data(), 0.0, nullptr,
                                static_cast<int>(packing.radius.size())};
  // in a tube every sphere lies inside the disk, whose area normalises the slab
  const double area = domain.has_cylinder
                          ? kPi * domain.cylinder.radius * domain.cylinder.radius
                          : (domain.xhi - domain.xlo) * (domain.yhi - domain.ylo);
  return stereo::horizontal_slab_volume(spheres, z0, z1) / (area * (z1 - z0));
}

}  // namespace tapmc
