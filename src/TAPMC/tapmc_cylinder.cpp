// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The vertical cylindrical container: validation, the wall, lenses and sphere-cylinder volumes.
#include "tapmc_cylinder.h"

#include "tapmc_checks.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
#include "tapmc_stereology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace tapmc {

// ---- validation and the wall --------------------------------------------------------------------

void validate(const Cylinder &cylinder)
{
  if (!std::isfinite(cylinder.cx)) throw_outside_range("cylinder cx", cylinder.cx, "(finite)");
  if (!std::isfinite(cylinder.cy)) throw_outside_range("cylinder cy", cylinder.cy, "(finite)");
  if (!(cylinder.radius > 0.0 && std::isfinite(cylinder.radius)))
    throw_outside_range("cylinder radius", cylinder.radius, "(0, +inf)");
}

void validate(const Cylinder &cylinder, double max_sphere_radius)
{
  if (!(max_sphere_radius > 0.0 && std::isfinite(max_sphere_radius)))
    throw_outside_range("largest sphere radius", max_sphere_radius, "(0, +inf)");
  validate(cylinder);
  if (!(cylinder.radius > max_sphere_radius))
    throw_outside_range("cylinder radius", cylinder.radius,
                        "(R_max, +inf) = (" + number(max_sphere_radius) +
                            ", +inf) (the container must be wider than its largest sphere)");
}

CylinderWall make_cylinder_wall(const Cylinder &cylinder, double max_sphere_radius,
                                double contact_tol)
{
  validate(cylinder, max_sphere_radius);
  if (!(contact_tol >= 0.0 && contact_tol < defaults::kMaxContactTolerance))
    throw_outside_range("contact_tol", contact_tol,
                        "[0, " + number(defaults::kMaxContactTolerance) + ")");
  CylinderWall wall;
  wall.cx = cylinder.cx;
  wall.cy = cylinder.cy;
  wall.radius = cylinder.radius;
  wall.tol = contact_tol;
  return wall;
}

std::vector<double> reach_sq_table(const CylinderWall &wall, const double *radius, int n)
{
  std::vector<double> table(std::max(0, n));
  for (int i = 0; i < n; ++i) table[i] = wall.reach_sq(radius[i]);
  return table;
}

// ---- disks --------------------------------------------------------------------------------------

namespace {

// Area of the circular segment of a disk of radius r cut off by a chord seen under the half-angle
// theta from the centre: r^2 (theta - sin theta cos theta) = r^2 (phi - sin phi) / 2, phi =
// 2 theta. For small phi the difference cancels (phi^3 / 6 of phi): a Taylor series then keeps
// the segment accurate relative to itself (thin lenses near tangency).
double segment_area(double r, double theta)
{
  const double phi = 2.0 * theta;
  double phi_minus_sin;
  if (phi < defaults::kLensSeriesAngle) {
    // phi - sin phi = sum_k (-1)^k phi^(2k+3) / (2k+3)!, terms through phi^13: at phi = 0.25
    // the first term left out is 1e-18 of the sum
    const double p2 = phi * phi;
    double term = phi * p2 / 6.0, sum = 0.0;
    for (int k = 0; k < 6; ++k) {
      sum += term;
      term *= -p2 / ((2 * k + 4) * (2 * k + 5));
    }
    phi_minus_sin = sum;
  } else {
    phi_minus_sin = phi - std::sin(phi);
  }
  return 0.5 * r * r * phi_minus_sin;
}

// Two circles of radii a and b, centres d apart, crossing (|a - b| < d < a + b): half the common
// chord h and the signed distance x_a of the chord from a's centre (towards b's). h^2 is the
// product of four factors each computed from the inputs directly (no difference of squares of
// nearly equal numbers), so h keeps its relative accuracy near tangency.
void common_chord(double a, double b, double d, double &h, double &x_a)
{
  const double prod = (a + b - d) * (d + a - b) * (d - a + b) * (a + b + d);
  h = std::sqrt(std::max(0.0, prod)) / (2.0 * d);
  x_a = (d * d + (a - b) * (a + b)) / (2.0 * d);
}

}  // namespace

double disk_lens_area(double a, double b, double d)
{
  if (!(a > 0.0 && b > 0.0)) return 0.0;
  if (a > b) std::swap(a, b);  // a <= b: the same arithmetic for (a, b) and (b, a)
  d = std::fabs(d);
  if (d >= a + b) return 0.0;
  if (d <= b - a) return kPi * a * a;
  double h, x_a;
  common_chord(a, b, d, h, x_a);
  // each disk contributes the segment beyond the chord; atan2 gives the half-angle with its
  // relative accuracy whatever the side of the chord the centre lies on
  return segment_area(a, std::atan2(h, x_a)) + segment_area(b, std::atan2(h, d - x_a));
}

double circle_arc_in_disk(double rho, double a, double d)
{
  if (!(rho > 0.0 && a > 0.0)) return 0.0;
  d = std::fabs(d);
  if (d + rho <= a) return kTwoPi * rho;         // the whole circle is inside the disk
  if (d >= a + rho || rho >= a + d) return 0.0;  // apart, or the disk inside the circle
  double h, x_rho;
  common_chord(rho, a, d, h, x_rho);
  return 2.0 * rho * std::atan2(h, x_rho);
}

// ---- a sphere and a coaxial cylinder ------------------------------------------------------------

namespace {

// Gauss-Legendre nodes and weights on [-1, 1], computed once (Newton's method on P_n from the
// Chebyshev-like first guesses; converges to rounding in a few steps for these n).
struct GaussLegendre {
  static constexpr int n = defaults::kCylinderQuadratureNodes;
  std::array<double, n> node{}, weight{};
  GaussLegendre()
  {
    for (int i = 0; i < (n + 1) / 2; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1.0, p1 = x;  // P_0, P_1, then the recurrence up to P_n
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / dp;
        x -= step;
        if (std::fabs(step) < 1e-17) break;
      }
      // one more derivative at the converged node for the weight
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double w = 2.0 / ((1.0 - x * x) * dp * dp);
      node[i] = x;
      node[n - 1 - i] = -x;
      weight[i] = weight[n - 1 - i] = w;
    }
  }
};

const GaussLegendre &gauss_legendre()
{
  static const GaussLegendre rule;
  return rule;
}

// Polar angle of the height z on a sphere of radius R (z = -R cos phi: 0 at the bottom pole, pi
// at the top), written with atan2 so that it keeps full accuracy near the poles.
double polar_angle(double R, double z)
{
  return std::atan2(std::sqrt(std::max(0.0, (R - z) * (R + z))), -z);
}

// Integral over z in [zlo, zhi] of cut(a(z)) dz, a(z) = sqrt(R^2 - z^2) the radius of the sphere's
// horizontal cut, where cut(a) (a lens area or an arc length against the cylinder of radius rho at
// distance d) is analytic in a except at the kinks a = |rho - d| and a = rho + d, where the lens
// meets or leaves tangency: the lens behaves like |a - a_k|^(3/2) there, the arc like
// |a - a_k|^(1/2).
//  - The variable is the polar angle phi (z = -R cos phi, dz = R sin phi dphi): a = R sin phi is
//    then analytic everywhere, so the square root of a(z) at the poles disappears.
//  - [phi(zlo), phi(zhi)] is split at the kinks (phi = asin(a_k / R) and pi - asin(a_k / R))
//    and at the equator phi = pi / 2, where a(phi) is largest: a kink a_k at or just above R
//    (the cylinder tangent to the sphere's equator from inside or outside) would otherwise put a
//    |phi - pi/2|^3 behaviour, or its rounded version, inside a piece (measured: errors of
//    2e-4 R^3 at rho + d = R without the split).
//  - On each piece, phi = mid + half (3 t - t^3) / 2 (t in [-1, 1]): dphi/dt vanishes like
//    (1 - t^2) at both ends, so |phi - phi_k|^(p/2) becomes |1 -+ t|^p, smooth for the odd
//    p = 1, 3 above, and Gauss-Legendre converges geometrically on every piece (a slab bound that
//    is not a kink is mapped too: the map only costs a few nodes on a smooth piece).
template <class Cut>
double integrate_over_height(double R, double d, double rho, double zlo, double zhi, Cut &&cut)
{
  const double lo = std::max(zlo, -R), hi = std::min(zhi, R);
  if (!(lo < hi)) return 0.0;
  std::array<double, 7> breaks{};
  int nb = 0;
  breaks[nb++] = polar_angle(R, lo);
  breaks[nb++] = polar_angle(R, hi);
  auto add_break = [&](double phi) {
    if (phi > breaks[0] && phi < breaks[1]) breaks[nb++] = phi;
  };
  add_break(0.5 * kPi);
  for (const double c : {std::fabs(rho - d), rho + d}) {
    if (!(c > 0.0 && c < R)) continue;
    const double phi_k = std::atan2(c, std::sqrt((R - c) * (R + c)));  // asin(c / R)
    add_break(phi_k);
    add_break(kPi - phi_k);
  }
  for (int i = 1; i < nb; ++i)  // insertion sort of at most seven angles
    for (int j = i; j > 0 && breaks[j] < breaks[j - 1]; --j) std::swap(breaks[j], breaks[j - 1]);
  const GaussLegendre &rule = gauss_legendre();
  double total = 0.0;
  for (int p = 0; p + 1 < nb; ++p) {
    const double half = 0.5 * (breaks[p + 1] - breaks[p]);
    if (!(half > 0.0)) continue;
    const double mid = 0.5 * (breaks[p + 1] + breaks[p]);
    double sum = 0.0;
    for (int i = 0; i < GaussLegendre::n; ++i) {
      const double t = rule.node[i];
      const double phi = mid + half * (0.5 * t * (3.0 - t * t));
      const double dphi_dt = 1.5 * (1.0 - t) * (1.0 + t);
      const double s = std::sin(phi);
      sum += rule.weight[i] * dphi_dt * s * cut(R * s);
    }
    total += half * sum;
  }
  return R * total;
}

}  // namespace

double sphere_cylinder_slab_volume(double R, double d, double rho, double zlo, double zhi)
{
  if (!(R > 0.0 && rho > 0.0)) return 0.0;
  d = std::fabs(d);
  if (d >= rho + R) return 0.0;                                      // outside the cylinder
  if (d + R <= rho) return stereo::sphere_slab_volume(R, zlo, zhi);  // wholly inside
  return integrate_over_height(R, d, rho, zlo, zhi,
                               [&](double a) { return disk_lens_area(a, rho, d); });
}

double sphere_cylinder_surface_area(double R, double d, double rho, double zlo, double zhi)
{
  if (!(R > 0.0 && rho > 0.0)) return 0.0;
  d = std::fabs(d);
  if (d >= rho + R || d + R <= rho) return 0.0;  // the surface misses the sphere
  return integrate_over_height(R, d, rho, zlo, zhi,
                               [&](double a) { return circle_arc_in_disk(rho, a, d); });
}

}  // namespace tapmc
