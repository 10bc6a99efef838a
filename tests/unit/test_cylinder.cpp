// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Unit tests of the cylindrical container: the wall test, validation, and its exact stereology.
#include "tapmc_contact.h"
#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"
#include "tapmc_stereology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using tapmc::stereo::PlaneGrid;
using tapmc::stereo::Spheres;

namespace {

std::string message_of(const std::function<void()> &f)
{
  try {
    f();
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

// ---- an independent oracle ----------------------------------------------------------------------
// Written apart from the kernel: the textbook lens formula (two acos terms minus the kite), the
// height z (not the polar angle) as the variable, and tanh-sinh (double exponential) quadrature,
// which converges geometrically also with algebraic singularities at the ends of each piece.
double tanh_sinh(const std::function<double(double)> &f, double a, double b, int levels = 64)
{
  if (!(a < b)) return 0.0;
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const double h = 1.0 / levels;
  double sum = 0.0;
  for (int k = -4 * levels; k <= 4 * levels; ++k) {  // t in [-4, 4]
    const double t = k * h;
    const double u = 0.5 * kPi * std::sinh(t);
    const double ch = std::cosh(u);
    // distance of the node from the nearer end, without the cancellation of 1 - tanh(u)
    const double gap = 1.0 / (std::exp(std::fabs(u)) * ch);
    const double w = 0.5 * kPi * std::cosh(t) / (ch * ch);
    if (w < 1e-300 || gap <= 0.0) continue;
    const double x = t < 0.0 ? a + half * gap : b - half * gap;
    sum += w * f(x);
  }
  return sum * h * half;
}

double piecewise(const std::function<double(double)> &f, double a, double b,
                 std::vector<double> breaks, int levels = 64)
{
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  double total = 0.0;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    if (lo < hi) total += tanh_sinh(f, lo, hi, levels);
  }
  return total;
}

double textbook_lens(double r1, double r2, double d)
{
  if (r1 <= 0.0 || r2 <= 0.0 || d >= r1 + r2) return 0.0;
  if (d <= std::fabs(r1 - r2)) return kPi * std::min(r1, r2) * std::min(r1, r2);
  const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0);
  const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0);
  const double kite =
      std::sqrt(std::max(0.0, (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2)));
  return r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * kite;
}

// Heights where the cut radius sqrt(R^2 - z^2) meets a lens kink |rho - d| or rho + d, and the
// equator z = 0, where the cut radius is largest (a kink equal to R touches it there).
std::vector<double> kink_heights(double R, double d, double rho)
{
  std::vector<double> z = {0.0};
  for (double c : {std::fabs(rho - d), rho + d})
    if (c < R) {
      const double h = std::sqrt(R * R - c * c);
      z.push_back(-h);
      z.push_back(h);
    }
  return z;
}

// Volume of sphere (R, centre at the origin) ∩ cylinder (rho, axis at distance d) ∩ slab.
double oracle_volume(double R, double d, double rho, double zlo, double zhi)
{
  return piecewise(
      [&](double z) { return textbook_lens(std::sqrt(std::max(0.0, R * R - z * z)), rho, d); },
      std::max(zlo, -R), std::min(zhi, R), kink_heights(R, d, rho));
}

// The same as a 2-D integral that uses no lens formula: at each height, over circles of radius s
// about the sphere's axis, the arc inside the cylinder's disk (2 s psi, psi by the cosine rule).
double oracle_volume_2d(double R, double d, double rho, double zlo, double zhi)
{
  auto arc = [&](double s) {
    if (s + d <= rho) return 2.0 * kPi * s;
    if (s >= rho + d || d >= s + rho) return 0.0;
    return 2.0 * s * std::acos(std::clamp((d * d + s * s - rho * rho) / (2.0 * d * s), -1.0, 1.0));
  };
  auto cut = [&](double z) {
    const double a = std::sqrt(std::max(0.0, R * R - z * z));
    return piecewise(arc, 0.0, a, {std::fabs(rho - d), rho + d}, 24);
  };
  return piecewise(cut, std::max(zlo, -R), std::min(zhi, R), kink_heights(R, d, rho), 24);
}

struct Packing {
  std::vector<double> xyz, radius;
  Spheres view() const
  {
    Spheres s;
    s.xyz = xyz.data();
    s.radius = radius.data();
    s.count = static_cast<int>(radius.size());
    return s;
  }
  void add(double x, double y, double z, double r)
  {
    for (double c : {x, y, z}) xyz.push_back(c);
    radius.push_back(r);
  }
};

// Random sequential addition of non-overlapping spheres (radii in [0.4, 0.6]) inside the
// cylinder, a quarter of them touching its wall (where the lens kinks sit at the poles or the
// equator of the sphere).
Packing random_packing(unsigned seed, const Cylinder &c, int count, double height)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Packing p;
  while (static_cast<int>(p.radius.size()) < count) {
    const double r = 0.4 + 0.2 * uni(rng);
    const double angle = 2.0 * kPi * uni(rng);
    const double dist = uni(rng) < 0.25 ? c.radius - r : (c.radius - r) * std::sqrt(uni(rng));
    const double x = c.cx + dist * std::cos(angle), y = c.cy + dist * std::sin(angle);
    const double z = r + (height - 2.0 * r) * uni(rng);
    bool free = true;
    for (size_t j = 0; j < p.radius.size() && free; ++j) {
      const double dx = x - p.xyz[3 * j], dy = y - p.xyz[3 * j + 1], dz = z - p.xyz[3 * j + 2];
      free = dx * dx + dy * dy + dz * dz >= (r + p.radius[j]) * (r + p.radius[j]);
    }
    if (free) p.add(x, y, z, r);
  }
  return p;
}

double axis_distance(const Packing &p, size_t i, const Cylinder &c)
{
  return std::hypot(p.xyz[3 * i] - c.cx, p.xyz[3 * i + 1] - c.cy);
}

}  // namespace

// ---- the container and its wall -----------------------------------------------------------------

TEST(CylinderWall, TouchingFromInsideIsAcceptedAHairBeyondIsNot)
{
  // exact cases: a 3-4-5 offset (centre 5 from the axis) and an axis-aligned one
  const Cylinder c{1.5, -2.25, 5.5};
  for (double tol : {0.0, defaults::kContactTolerance}) {
    const CylinderWall wall = make_cylinder_wall(c, 0.5, tol);
    EXPECT_TRUE(wall.contains_sphere(1.5 + 3.0, -2.25 + 4.0, 0.5)) << tol;
    EXPECT_TRUE(wall.contains_sphere(1.5 - 5.0, -2.25, 0.5)) << tol;
    EXPECT_TRUE(wall.contains_sphere(1.5, -2.25, 0.5)) << tol;
    EXPECT_EQ(wall.gap(1.5 + 3.0, -2.25 + 4.0, 0.5), 0.0);
    EXPECT_EQ(wall.gap(1.5, -2.25, 0.5), 5.0);
  }
  const CylinderWall exact = make_cylinder_wall(c, 0.5, 0.0);
  // a hair beyond: the offset from the axis one ulp longer (these sums are exact)
  EXPECT_FALSE(exact.contains_sphere(1.5 + std::nextafter(-5.0, -10.0), -2.25, 0.5));
  EXPECT_FALSE(exact.contains_sphere(1.5 + 3.0, -2.25 + std::nextafter(4.0, 10.0), 0.5));
  double gap = 0.0;
  EXPECT_TRUE(cylinder_violation(exact, 1.5 + 3.0 + 1e-9, -2.25 + 4.0, 0.5, gap));
  EXPECT_LT(gap, 0.0);
  EXPECT_FALSE(cylinder_violation(exact, 1.5 + 3.0, -2.25 + 4.0, 0.5, gap));
  EXPECT_EQ(gap, 0.0);
  // a sphere wider than the container is never inside (the reach is negative)
  EXPECT_EQ(cylinder_reach_sq(1.0, 2.0, 0.0), -1.0);
  EXPECT_FALSE(exact.contains_sphere(1.5, -2.25, 6.0));
}

TEST(CylinderWall, ToleranceMirrorsTheFlatWalls)
{
  // The flat wall x = cx + radius and the cylinder, approached along +x from inside: the same
  // verdict at every overshoot of the sphere's surface beyond the wall, in units of tol (2 r),
  // away from the threshold by more than rounding.
  for (double tol : {defaults::kContactTolerance, 1e-6, 0.05}) {
    for (double r : {0.25, 1.0, 3.0}) {
      const Cylinder c{0.75, 2.0, 7.0};
      const CylinderWall wall = make_cylinder_wall(c, r, tol);
      for (double s : {-1.0, 0.0, 0.5, 0.999, 1.001, 1.5, 3.0}) {
        const double overshoot = s * tol * (2.0 * r);
        const double x = c.cx + (c.radius - r) + overshoot;
        double flat_gap = 0.0;
        const bool flat = side_wall_violation(0, x, r, -1e9, c.cx + c.radius, tol, flat_gap) != 0;
        double cyl_gap = 0.0;
        const bool cyl = cylinder_violation(wall, x, c.cy, r, cyl_gap);
        EXPECT_EQ(cyl, flat) << "tol " << tol << " r " << r << " s " << s;
        EXPECT_EQ(cyl, s > 1.0);
        EXPECT_NEAR(cyl_gap, flat_gap, 1e-14 * c.radius);
      }
    }
  }
}

TEST(CylinderWall, PerRadiusTableMatchesTheMonodisperseReach)
{
  const CylinderWall wall = make_cylinder_wall(Cylinder{0.0, 0.0, 4.0}, 1.2, 1e-3);
  const std::vector<double> radii = {0.5, 1.0, 1.2};
  const std::vector<double> table = reach_sq_table(wall, radii.data(), 3);
  ASSERT_EQ(table.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(table[i], wall.reach_sq(radii[i]));
    const double reach = (4.0 - radii[i]) + 1e-3 * 2.0 * radii[i];
    EXPECT_EQ(table[i], reach * reach);
    // the table and the per-sphere call agree on a point just inside and just outside
    EXPECT_TRUE(wall.contains(reach * 0.999999, 0.0, table[i]));
    EXPECT_FALSE(wall.contains(0.0, reach * 1.000001, table[i]));
  }
}

TEST(CylinderValidation, MessagesNameTheArgumentValueAndRange)
{
  EXPECT_EQ(message_of([] {
              validate(Cylinder{0.0, 0.0, -1.0});
            }),
            "cylinder radius = -1 is outside the allowed range (0, +inf)");
  EXPECT_EQ(message_of([] {
              validate(Cylinder{0.0, 0.0, 0.0});
            }),
            "cylinder radius = 0 is outside the allowed range (0, +inf)");
  EXPECT_EQ(message_of([] {
              validate(Cylinder{std::nan(""), 0.0, 1.0});
            }),
            "cylinder cx = nan is outside the allowed range (finite)");
  EXPECT_EQ(message_of([] {
              validate(Cylinder{0.0, std::numeric_limits<double>::infinity(), 1.0});
            }),
            "cylinder cy = inf is outside the allowed range (finite)");
  EXPECT_EQ(message_of([] {
              validate(Cylinder{0.0, 0.0, 0.4}, 0.5);
            }),
            "cylinder radius = 0.4 is outside the allowed range (R_max, +inf) = (0.5, +inf) "
            "(the container must be wider than its largest sphere)");
  EXPECT_NE(message_of([] { validate(Cylinder{0.0, 0.0, 0.5}, 0.5); }), "");  // equal: no room
  EXPECT_EQ(message_of([] { validate(Cylinder{0.0, 0.0, 0.51}, 0.5); }), "");
  EXPECT_EQ(message_of([] {
              make_cylinder_wall(Cylinder{0.0, 0.0, 2.0}, 0.5, 0.2);
            }),
            "contact_tol = 0.2 is outside the allowed range [0, 0.1)");
  EXPECT_EQ(message_of([] {
              make_cylinder_wall(Cylinder{0.0, 0.0, 2.0}, -0.5, 0.0);
            }),
            "largest sphere radius = -0.5 is outside the allowed range (0, +inf)");
  Packing p;
  p.add(0, 0, 1, 0.5);
  EXPECT_EQ(message_of([&] {
              stereo::radial_profile(p.view(), Cylinder{0, 0, 2}, PlaneGrid{-0.5, 2.0, 4}, 0, 2);
            }),
            "radial bins lo = -0.5 is outside the allowed range [0, hi)");
  EXPECT_EQ(message_of([&] {
              stereo::cylinder_zones(p.view(), Cylinder{0, 0, 2}, 0.0, 0, 2);
            }),
            "wall zone width = 0 is outside the allowed range (0, +inf)");
  EXPECT_EQ(message_of([&] {
              stereo::cylinder_profile(p.view(), Cylinder{0, 0, -2}, PlaneGrid{});
            }),
            "cylinder radius = -2 is outside the allowed range (0, +inf)");
}

// ---- one sphere and a coaxial cylinder ----------------------------------------------------------

TEST(CylinderGeometry, LensAreaSpecialCasesAndTextbookFormula)
{
  EXPECT_EQ(disk_lens_area(1.0, 2.0, 3.0), 0.0);
  EXPECT_EQ(disk_lens_area(1.0, 2.0, 1.0), kPi);  // internally tangent: the small disk
  EXPECT_EQ(disk_lens_area(0.0, 2.0, 0.5), 0.0);
  EXPECT_NEAR(disk_lens_area(1.0, 1.0, 0.0), kPi, 1e-15);
  // two unit disks one radius apart: 2 pi / 3 - sqrt(3) / 2
  EXPECT_NEAR(disk_lens_area(1.0, 1.0, 1.0), 2.0 * kPi / 3.0 - std::sqrt(3.0) / 2.0, 1e-15);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.05, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const double a = u(rng), b = u(rng), d = u(rng);
    EXPECT_NEAR(disk_lens_area(a, b, d), textbook_lens(a, b, d),
                2e-14 * std::max(a, b) * std::max(a, b));
    EXPECT_EQ(disk_lens_area(a, b, d), disk_lens_area(b, a, d));
  }
  // Thin lenses near tangency keep their relative accuracy (the textbook form loses it): two
  // unit disks d = 2 - e apart overlap in two equal segments of half-angle theta,
  // 2 (theta - sin theta cos theta) = 4/3 theta^3 - 4/15 theta^5 + O(theta^7).
  for (double e : {1e-4, 1e-6, 1e-8}) {
    const double d = 2.0 - e;
    // 1 - d / 2 is exact (Sterbenz): theta from its sine keeps full accuracy
    const double theta = std::asin(std::sqrt((1.0 - 0.5 * d) * (1.0 + 0.5 * d)));
    const double series = 2.0 * (2.0 * std::pow(theta, 3) / 3.0 - 2.0 * std::pow(theta, 5) / 15.0);
    EXPECT_NEAR(disk_lens_area(1.0, 1.0, d) / series, 1.0,
                1e-13 + theta * theta * theta * theta)
        << e;
  }
  // the arc is the derivative of the lens in the circle's radius
  for (double rho : {0.3, 1.0, 1.7}) {
    const double h = 1e-5;
    const double fd =
        (disk_lens_area(1.2, rho + h, 0.8) - disk_lens_area(1.2, rho - h, 0.8)) / (2 * h);
    EXPECT_NEAR(circle_arc_in_disk(rho, 1.2, 0.8), fd, 1e-8) << rho;
  }
}

TEST(CylinderGeometry, SphereOnTheAxisHasTheClosedForm)
{
  // A sphere of radius R on the axis of a cylinder of radius rho < R: the cylinder holds a
  // straight part of height 2 h (h = sqrt(R^2 - rho^2)) and two caps of height R - h:
  //   V = 2 pi rho^2 h + 2 pi (R - h)^2 (2 R + h) / 3 = 4/3 pi (R^3 - h^3)
  // (the sphere minus the "napkin ring" of half-height h, whose volume is 4/3 pi h^3).
  for (double R : {0.5, 1.0, 2.3}) {
    for (double f : {0.01, 0.3, 0.7071, 0.99, 0.999999}) {
      const double rho = f * R;
      const double h = std::sqrt((R - rho) * (R + rho));  // no cancellation as rho -> R
      const double parts =
          2.0 * kPi * rho * rho * h + 2.0 * kPi * (R - h) * (R - h) * (2.0 * R + h) / 3.0;
      const double ring = 4.0 / 3.0 * kPi * (R * R * R - h * h * h);
      EXPECT_NEAR(parts, ring, 1e-14 * R * R * R);
      EXPECT_NEAR(sphere_cylinder_slab_volume(R, 0.0, rho, -10.0, 10.0), ring, 1e-14 * R * R * R)
          << R << " " << f;
      // the upper half only, and the surface: 2 pi rho (2 h)
      EXPECT_NEAR(sphere_cylinder_slab_volume(R, 0.0, rho, 0.0, 10.0), 0.5 * ring,
                  1e-14 * R * R * R);
      EXPECT_NEAR(sphere_cylinder_surface_area(R, 0.0, rho, -10.0, 10.0), 4.0 * kPi * rho * h,
                  1e-13 * R * R);
    }
  }
}

TEST(CylinderGeometry, WholeAndEmptyCases)
{
  const double R = 0.8;
  for (double d : {0.0, 0.3, 2.0}) {
    // rho >= d + R: the whole slab of the sphere
    EXPECT_EQ(sphere_cylinder_slab_volume(R, d, d + R, -0.2, 5.0),
              stereo::sphere_slab_volume(R, -0.2, 5.0));
    EXPECT_NEAR(sphere_cylinder_slab_volume(R, d, d + R + 1.0, -9.0, 9.0), 4.0 / 3.0 * kPi * 0.512,
                1e-15);
    EXPECT_EQ(sphere_cylinder_surface_area(R, d, d + R, -9.0, 9.0), 0.0);
  }
  // rho <= d - R: nothing
  EXPECT_EQ(sphere_cylinder_slab_volume(R, 2.0, 1.2, -9.0, 9.0), 0.0);
  EXPECT_EQ(sphere_cylinder_slab_volume(R, 2.0, 0.5, -9.0, 9.0), 0.0);
  EXPECT_EQ(sphere_cylinder_slab_volume(R, 0.5, 0.0, -9.0, 9.0), 0.0);
  EXPECT_EQ(sphere_cylinder_slab_volume(R, 0.5, 1.0, 0.9, 2.0), 0.0);  // slab above the sphere
  // The half-space limit: a huge cylinder whose wall passes through the sphere's centre holds
  // half of it, up to the wall's curvature (sagitta R^2 / (2 rho): 3e-7 of the volume here).
  const double big = 1e6;
  EXPECT_NEAR(sphere_cylinder_slab_volume(R, big, big, -9.0, 9.0), 2.0 / 3.0 * kPi * 0.512, 1e-6);
}

TEST(CylinderGeometry, VolumeMatchesTheIndependentQuadratures)
{
  // Random spheres, cylinders and slabs, plus the hard cases: kinks at the poles (rho = d), at
  // the equator (|rho - d| = R or rho + d = R), a pole grazing the slab, d = 0.
  struct Case {
    double R, d, rho, zlo, zhi;
  };
  std::vector<Case> cases = {{1.0, 0.5, 0.5, -2, 2},
                             {1.0, 0.5, 1.5, -2, 2},
                             {1.0, 0.3, 0.7, -2, 2},
                             {1.0, 1e-9, 0.4, -2, 2},
                             {1.0, 0.5, 0.5 + 1e-7, -0.999999, 2},
                             {1.0, 2.0, 1.0000001, -2, 2},
                             {1.0, 0.25, 0.75, -0.3, 0.31},
                             {0.6, 5.0 - 0.6, 5.0, -1, 1}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const double R = 0.3 + u(rng), d = 2.5 * u(rng), rho = 0.01 + 3.0 * u(rng);
    const double z0 = -1.5 * R + 2.0 * R * u(rng), z1 = z0 + 2.0 * R * u(rng);
    cases.push_back({R, d, rho, z0, z1});
  }
  double worst = 0.0;
  for (const Case &c : cases) {
    const double got = sphere_cylinder_slab_volume(c.R, c.d, c.rho, c.zlo, c.zhi);
    const double want = oracle_volume(c.R, c.d, c.rho, c.zlo, c.zhi);
    const double scale = c.R * c.R * c.R;
    worst = std::max(worst, std::fabs(got - want) / scale);
    EXPECT_NEAR(got, want, 1e-13 * scale)
        << "R " << c.R << " d " << c.d << " rho " << c.rho << " z " << c.zlo << " " << c.zhi;
  }
  std::printf("sphere-cylinder volume vs 1-D oracle: worst error %.2e R^3 over %zu cases\n", worst,
              cases.size());
  // The 2-D oracle (no lens formula) on the hard cases and a few random ones.
  double worst2 = 0.0;
  for (size_t i = 0; i < 16; ++i) {
    const Case &c = cases[i];
    const double got = sphere_cylinder_slab_volume(c.R, c.d, c.rho, c.zlo, c.zhi);
    const double want = oracle_volume_2d(c.R, c.d, c.rho, c.zlo, c.zhi);
    worst2 = std::max(worst2, std::fabs(got - want) / (c.R * c.R * c.R));
    EXPECT_NEAR(got, want, 1e-13 * c.R * c.R * c.R) << i;
  }
  std::printf("sphere-cylinder volume vs 2-D oracle: worst error %.2e R^3\n", worst2);
}

TEST(CylinderGeometry, SurfaceIntegratesToTheVolume)
{
  // V(rho2) - V(rho1) = integral of the surface area over rho (the cut of a cylindrical surface
  // integrates to the volume between, as plane cuts do).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    const double R = 0.5 + u(rng), d = 2.0 * u(rng);
    const double zlo = -R + 1.5 * R * u(rng), zhi = zlo + R * u(rng) + 0.05;
    const double r1 = 3.0 * u(rng), r2 = r1 + 1.5 * u(rng);
    // breaks where the integrand is not smooth in rho: the sphere's reach, and where a kink
    // meets a slab bound or the equator
    std::vector<double> breaks = {std::fabs(d - R), d + R, R - d};
    for (double z : {zlo, zhi, 0.0})
      if (std::fabs(z) < R) {
        const double a = std::sqrt(R * R - z * z);
        for (double b : {d - a, d + a, a - d}) breaks.push_back(b);
      }
    const double integral =
        piecewise([&](double rho) { return sphere_cylinder_surface_area(R, d, rho, zlo, zhi); }, r1,
                  r2, breaks);
    const double diff = sphere_cylinder_slab_volume(R, d, r2, zlo, zhi) -
                        sphere_cylinder_slab_volume(R, d, r1, zlo, zhi);
    EXPECT_NEAR(integral, diff, 1e-11 * R * R * R) << i;
  }
}

// ---- stereology of a packing in the tube --------------------------------------------------------

TEST(CylinderStereology, AnnuliTileTheSlabVolume)
{
  const Cylinder c{1.25, -0.5, 5.0};
  const Packing p = random_packing(3, c, 200, 10.0);
  const Spheres s = p.view();
  for (double za : {-1.0, 2.3}) {
    const double zb = za + 4.1;
    const std::vector<double> rows =
        stereo::radial_profile(s, c, PlaneGrid{0.0, c.radius, 13}, za, zb);
    double total = 0.0;
    const double w = c.radius / 13;
    for (int k = 0; k < 13; ++k) {
      const double r0 = k * w, r1 = r0 + w;
      total += rows[3 * k + 2] * kPi * (r1 * r1 - r0 * r0) * (zb - za);
    }
    const double slab = stereo::horizontal_slab_volume(s, za, zb);
    EXPECT_NEAR(total, slab, 1e-12 * slab) << za;
    // the same through the disk profile and the zones: every sphere is inside, so the volume
    // over the disk is the box's closed form
    EXPECT_NEAR(stereo::cylinder_slab_volume(s, c, za, zb), slab, 1e-13 * slab);
    double sums[stereo::kNumCylinderZoneSums] = {};
    stereo::accumulate_cylinder_zones(s, c, 3.5, za, zb, sums);
    EXPECT_NEAR(sums[stereo::kCylinderWallVolume] + sums[stereo::kCylinderCoreVolume], slab,
                1e-12 * slab);
  }
}

TEST(CylinderStereology, RadialProfileMatchesTheOracleOnARandomPacking)
{
  const Cylinder c{-0.75, 2.0, 5.0};
  const Packing p = random_packing(17, c, 200, 10.0);
  const Spheres s = p.view();
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 4; ++trial) {
    const double lo = 2.0 * u(rng), hi = lo + 0.5 + (c.radius - lo) * u(rng);
    const int n = 3 + static_cast<int>(6 * u(rng));
    const double za = 10.0 * u(rng) - 1.0, zb = za + 0.5 + 6.0 * u(rng);
    const PlaneGrid grid{lo, hi, n};
    std::vector<double> cut(n, 0.0), vol(n, 0.0);
    stereo::accumulate_radial_profile(s, c, grid, za, zb, cut.data(), vol.data());
    for (int k = 0; k < n; ++k) {
      const double r0 = lo + k * grid.bin_width(), r1 = r0 + grid.bin_width();
      double want = 0.0;
      for (size_t i = 0; i < p.radius.size(); ++i) {
        const double d = axis_distance(p, i, c), R = p.radius[i], zc = p.xyz[3 * i + 2];
        want +=
            oracle_volume(R, d, r1, za - zc, zb - zc) - oracle_volume(R, d, r0, za - zc, zb - zc);
      }
      const double err = std::fabs(vol[k] - want) / std::max(want, 1e-300);
      worst = std::max(worst, err);
      // the issue asks 1e-9; measured ~1e-13 (the kernel's ~1e-15 R^3 over bins of ~10 R^3)
      EXPECT_LT(err, 1e-11) << "trial " << trial << " bin " << k << " got " << vol[k] << " want "
                           << want;
    }
  }
  std::printf("radial annulus volumes vs oracle (200 spheres): worst relative error %.2e\n", worst);
}

TEST(CylinderStereology, DiskProfileCountsOnlyWhatIsInsideTheDisk)
{
  // An invalid packing (centres up to 0.5 beyond the wall): Phi(z) over the disk counts only
  // the parts inside; checked against the oracle bin by bin and plane by plane.
  const Cylinder c{0.5, 0.25, 3.0};
  Packing p;
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 120; ++i) {
    const double angle = 2.0 * kPi * u(rng), dist = (c.radius + 0.5) * std::sqrt(u(rng));
    p.add(c.cx + dist * std::cos(angle), c.cy + dist * std::sin(angle), 6.0 * u(rng),
          0.3 + 0.4 * u(rng));
  }
  const Spheres s = p.view();
  const PlaneGrid grid{-0.5, 6.5, 9};
  const std::vector<double> rows = stereo::cylinder_profile(s, c, grid);
  const double area = kPi * c.radius * c.radius;
  double worst = 0.0;
  for (int k = 0; k < grid.n; ++k) {
    const double z0 = grid.lo + k * grid.bin_width(), z1 = z0 + grid.bin_width();
    double vol = 0.0, cut = 0.0;
    for (size_t i = 0; i < p.radius.size(); ++i) {
      const double d = axis_distance(p, i, c), R = p.radius[i], zc = p.xyz[3 * i + 2];
      vol += oracle_volume(R, d, c.radius, z0 - zc, z1 - zc);
      const double uu = grid.position(k) - zc;
      if (std::fabs(uu) < R) cut += textbook_lens(std::sqrt(R * R - uu * uu), c.radius, d);
    }
    const double phi_bin = vol / (area * grid.bin_width());
    worst = std::max(worst, std::fabs(rows[3 * k + 2] - phi_bin) / phi_bin);
    EXPECT_NEAR(rows[3 * k + 2], phi_bin, 1e-10 * phi_bin) << k;
    EXPECT_NEAR(rows[3 * k + 1], cut / area, 1e-12) << k;
    EXPECT_NEAR(rows[3 * k + 1], stereo::cylinder_cut_area(s, c, grid.position(k)) / area, 1e-15);
  }
  std::printf("disk profile (spheres poking out) vs oracle: worst relative error %.2e\n", worst);
  // what pokes out is not counted: less than the box's whole-sphere volume
  EXPECT_LT(stereo::cylinder_slab_volume(s, c, -1.0, 7.0),
            stereo::horizontal_slab_volume(s, -1.0, 7.0) - 0.1);
}

TEST(CylinderStereology, WallZoneAndCoreAsFig8)
{
  // The wall zone within w of the wall and the core inside it, against the annulus volumes of
  // the radial profile with one boundary at radius - w (the same exact volumes).
  const Cylinder c{0.0, 0.0, 8.0};
  const Packing p = random_packing(41, c, 200, 12.0);
  const Spheres s = p.view();
  const double w = defaults::kLateralWidthOverRadius * 0.5;  // 7 R at R = 0.5
  const double za = 1.0, zb = 9.0;
  const stereo::CylinderZones z = stereo::cylinder_zones(s, c, w, za, zb);
  EXPECT_EQ(z.core_radius, 4.5);
  const std::vector<double> rows = stereo::radial_profile(s, c, PlaneGrid{0.0, 9.0, 2}, za, zb);
  // bins [0, 4.5] (the core) and [4.5, 9] (the wall zone and beyond, where nothing is)
  EXPECT_NEAR(z.phi_core, rows[2], 1e-13);
  const double vol_outer = rows[5] * kPi * (81.0 - 20.25) * (zb - za);
  EXPECT_NEAR(z.phi_wall, vol_outer / (kPi * (64.0 - 20.25) * (zb - za)), 1e-13);
  EXPECT_GT(z.phi_wall, 0.0);
  EXPECT_GT(z.phi_core, 0.0);
  // an empty window (zb <= za) has no coaxial surface: NaN rows, not zeros
  const std::vector<double> empty = stereo::radial_profile(s, c, PlaneGrid{0.0, 9.0, 2}, zb, za);
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(std::isnan(empty[3 * k + 1])) << k;
    EXPECT_TRUE(std::isnan(empty[3 * k + 2])) << k;
  }
  // a wall zone wider than the radius leaves no core: NaN, not a zero
  const stereo::CylinderZones all = stereo::cylinder_zones(s, c, 9.0, za, zb);
  EXPECT_TRUE(std::isnan(all.phi_core));
  EXPECT_NEAR(all.phi_wall, stereo::cylinder_slab_volume(s, c, za, zb) / (64.0 * kPi * 8.0), 1e-13);
}

TEST(CylinderStereology, RadialSurfaceCutsAverageToTheAnnulus)
{
  // Phi on the coaxial surfaces (column 2) averaged over the radius with weight 2 pi r is the
  // annulus fraction: checked by refining the grid (midpoint rule in r, error O(w^2)).
  const Cylinder c{0.0, 0.0, 4.0};
  const Packing p = random_packing(43, c, 80, 8.0);
  const Spheres s = p.view();
  const double za = 1.5, zb = 6.0;
  const std::vector<double> coarse = stereo::radial_profile(s, c, PlaneGrid{1.0, 3.0, 1}, za, zb);
  const int n = 400;
  const std::vector<double> fine = stereo::radial_profile(s, c, PlaneGrid{1.0, 3.0, n}, za, zb);
  double vol = 0.0;
  for (int k = 0; k < n; ++k) {
    const double r = fine[3 * k];
    vol += fine[3 * k + 1] * 2.0 * kPi * r * (zb - za) * (2.0 / n);
  }
  const double phi = vol / (kPi * (9.0 - 1.0) * (zb - za));
  EXPECT_NEAR(phi, coarse[2], 1e-4);
}

TEST(CylinderStereology, SummaryOverTheDiskAndTheWallZone)
{
  // The global measures in the tube (compute stereo/profile with a container): with every
  // sphere inside, Phi_b and <Phi^c> are the box's closed-form slab volumes over pi Rc^2; the
  // wall zone and the core are cylinder_zones over the window; h_s is the mean column top over
  // the container's bounding square.
  const Cylinder c{0.5, -1.0, 4.5};
  const Packing p = random_packing(47, c, 150, 9.0);
  const Spheres s = p.view();
  stereo::SummarySettings set;
  set.floor = 0.0;
  set.column_width = 1.5;
  const stereo::Summary sum = stereo::summarize_cylinder(s, c, set);
  const double R = stereo::mean_radius(s);
  const double area = kPi * c.radius * c.radius;

  // h_s by hand: 6 x 6 columns of 1.5 over [cx - Rc, cx + Rc] x [cy - Rc, cy + Rc]
  std::vector<double> tops(36, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < p.radius.size(); ++i) {
    const int ix = std::clamp(static_cast<int>((p.xyz[3 * i] - (c.cx - c.radius)) / 1.5), 0, 5);
    const int iy =
        std::clamp(static_cast<int>((p.xyz[3 * i + 1] - (c.cy - c.radius)) / 1.5), 0, 5);
    tops[6 * iy + ix] = std::max(tops[6 * iy + ix], p.xyz[3 * i + 2] + p.radius[i]);
  }
  double top_sum = 0.0;
  int filled = 0;
  for (double t : tops)
    if (std::isfinite(t)) top_sum += t, ++filled;
  EXPECT_NEAR(sum.surface, top_sum / filled, 1e-13);
  EXPECT_NEAR(sum.top, 0.9 * sum.surface, 1e-13);

  EXPECT_NEAR(sum.phi_bulk, stereo::horizontal_slab_volume(s, 0.0, 4.0 * R) / (area * 4.0 * R),
              1e-14);
  const double corrected = (16.0 / 11.0 * stereo::horizontal_slab_volume(s, 0.0, R) +
                            stereo::horizontal_slab_volume(s, R, sum.top)) /
                           (area * sum.top);
  EXPECT_NEAR(sum.phi_corrected, corrected, 1e-14);
  double height = 0.0;
  for (size_t i = 0; i < p.radius.size(); ++i) height += p.xyz[3 * i + 2];
  EXPECT_NEAR(sum.mean_height, height / p.radius.size(), 1e-13);
  const stereo::CylinderZones z = stereo::cylinder_zones(s, c, 7.0 * R, 2.0 * R, sum.top);
  EXPECT_GT(z.phi_wall, 0.1);  // both zones hold material
  EXPECT_GT(z.phi_core, 0.1);
  EXPECT_NEAR(sum.phi_lateral, z.phi_wall, 1e-14);
  EXPECT_NEAR(sum.phi_central, z.phi_core, 1e-14);

  // the sums add up over parts of the packing (what the MPI reduction relies on)
  const stereo::Box box = stereo::bounding_box(c, 0.0, 9.0);
  const stereo::Windows w = stereo::resolve_windows(set, box, R, sum.surface);
  std::vector<int> even, odd;
  for (int i = 0; i < s.count; ++i) (i % 2 ? odd : even).push_back(i);
  double whole[stereo::kNumSummarySums] = {}, parts[stereo::kNumSummarySums] = {};
  stereo::accumulate_cylinder_summary(s, c, w, whole);
  for (const std::vector<int> *part : {&even, &odd}) {
    Spheres q = s;
    q.index = part->data();
    q.count = static_cast<int>(part->size());
    stereo::accumulate_cylinder_summary(q, c, w, parts);
  }
  for (int k = 0; k < stereo::kNumSummarySums; ++k)
    EXPECT_NEAR(parts[k], whole[k], 1e-12 * (1.0 + std::fabs(whole[k]))) << k;

  // a wall zone reaching the axis leaves no core: NaN, and the wall zone is the whole disk
  set.lateral_width = c.radius;
  const stereo::Summary all = stereo::summarize_cylinder(s, c, set);
  EXPECT_TRUE(std::isnan(all.phi_central));
  EXPECT_NEAR(all.phi_lateral,
              stereo::horizontal_slab_volume(s, 2.0 * R, all.top) /
                  (area * (all.top - 2.0 * R)),
              1e-13);
}

TEST(CylinderStereology, SummaryCountsOnlyWhatIsInsideTheContainer)
{
  // Spheres poking through the wall: Phi_b is the volume inside the container over the disk.
  const Cylinder c{0.0, 0.0, 3.0};
  Packing p;
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 80; ++i) {
    const double angle = 2.0 * kPi * u(rng), dist = (c.radius + 0.4) * std::sqrt(u(rng));
    p.add(dist * std::cos(angle), dist * std::sin(angle), 0.5 + 5.0 * u(rng), 0.5);
  }
  const Spheres s = p.view();
  stereo::SummarySettings set;
  set.floor = 0.0;
  const stereo::Summary sum = stereo::summarize_cylinder(s, c, set);
  const double inside = stereo::cylinder_slab_volume(s, c, 0.0, 2.0);
  EXPECT_NEAR(sum.phi_bulk, inside / (kPi * 9.0 * 2.0), 1e-14);
  EXPECT_LT(inside, stereo::horizontal_slab_volume(s, 0.0, 2.0) - 0.05);
}
