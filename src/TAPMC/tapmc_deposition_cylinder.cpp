// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The sequential deposition in a vertical cylindrical container (the tube): where a circle enters
// the wall, the roll on one sphere along the wall (its rest, its start, its next event), the
// checks of a tube domain, and which spheres of a packing the wall holds.
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
#include "tapmc_checks.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_deposition_grid.h"
#include "tapmc_deposition_roots.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace tapmc {
namespace deposition_detail {

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

// ---------------------------------------------------------------------------------------------
// The roll on one sphere j along the cylinder wall (the active set {j, wall}; its path is the
// WallRoll of tapmc_deposition_detail.h).

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

// ---------------------------------------------------------------------------------------------
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

}  // namespace deposition_detail

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
    out[i] = (c.radius - r) - h <= defaults::kDepositionSupportTolerance * 2.0 * r ? 1 : 0;
  }
  return out;
}

}  // namespace tapmc
