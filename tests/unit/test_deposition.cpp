// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the sequential-deposition kernel: analytic rests, brute-force overlap and stability
// oracles over many seeds (PBC, FBC, polydisperse), and the bulk packing fraction.
#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_deposition_grid.h"
#include "tapmc_math.h"
#include "tapmc_stereology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using tapmc::deposit_packing;
using tapmc::DepositionDomain;
using tapmc::Packing;
using tapmc::RadiusDistribution;
using tapmc::RestingOn;
using tapmc::SequentialDeposition;

namespace {

using tapmc::kPi;
constexpr double kSupportTol = tapmc::defaults::kDepositionSupportTolerance;
constexpr double kOverlapTol = tapmc::defaults::kContactTolerance;
// Barycentric coordinates / support forces accepted down to -kBalanceTol (dimensionless).
constexpr double kBalanceTol = 1e-9;

DepositionDomain make_domain(double lx, double ly, bool px, bool py)
{
  DepositionDomain d;
  d.xlo = 0.0;
  d.xhi = lx;
  d.ylo = 0.0;
  d.yhi = ly;
  d.periodic_x = px;
  d.periodic_y = py;
  d.z_floor = 0.0;
  return d;
}

// ---- independent oracles (no code shared with the kernel) -----------------------------------

struct Point {
  double x, y, z;
};

Point centre(const Packing &p, std::size_t i)
{
  return {p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]};
}

// Largest relative overlap (D - |r_ij|) / D over all pairs and all periodic images within
// one box length, and over floor and walls ((penetration) / diameter). <= 0 means none.
double worst_overlap(const Packing &p, const DepositionDomain &d)
{
  const std::size_t n = p.radius.size();
  const double lx = d.xhi - d.xlo, ly = d.yhi - d.ylo;
  double worst = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point a = centre(p, i);
    const double ra = p.radius[i];
    worst = std::max(worst, (d.z_floor - (a.z - ra)) / (2 * ra));
    if (!d.periodic_x) {
      worst = std::max(worst, (d.xlo - (a.x - ra)) / (2 * ra));
      worst = std::max(worst, ((a.x + ra) - d.xhi) / (2 * ra));
    }
    if (!d.periodic_y) {
      worst = std::max(worst, (d.ylo - (a.y - ra)) / (2 * ra));
      worst = std::max(worst, ((a.y + ra) - d.yhi) / (2 * ra));
    }
    for (std::size_t j = 0; j < i; ++j) {
      const Point b = centre(p, j);
      const double dist = ra + p.radius[j];
      for (int ix = d.periodic_x ? -1 : 0; ix <= (d.periodic_x ? 1 : 0); ++ix)
        for (int iy = d.periodic_y ? -1 : 0; iy <= (d.periodic_y ? 1 : 0); ++iy) {
          const double dx = a.x - b.x + ix * lx, dy = a.y - b.y + iy * ly, dz = a.z - b.z;
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 >= dist * dist) continue;
          worst = std::max(worst, (dist - std::sqrt(r2)) / dist);
        }
    }
  }
  return worst;
}

struct Support {
  bool wall;
  double x, y, z;   // sphere: image centre
  double nx, ny;    // wall: horizontal unit normal into the box
};

// 3x3 force balance: sum mu_q n_q = e_z with mu_q >= -tol, for three unit normals.
bool balances_gravity(const double n[3][3])
{
  auto det3 = [](const double a[3], const double b[3], const double c[3]) {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
  };
  const double det = det3(n[0], n[1], n[2]);
  if (std::fabs(det) < 1e-12) return false;
  const double ez[3] = {0, 0, 1};
  const double mu0 = det3(ez, n[1], n[2]) / det;
  const double mu1 = det3(n[0], ez, n[2]) / det;
  const double mu2 = det3(n[0], n[1], ez) / det;
  return mu0 >= -kBalanceTol && mu1 >= -kBalanceTol && mu2 >= -kBalanceTol;
}

// Sphere i is stable: on the floor, or three of the supports present when it came to rest
// (earlier spheres and walls it touches) hold it. For three spheres whose centres lie below
// its centre: its centre's vertical projection is inside their triangle (barycentric
// coordinates >= -tol). Otherwise (a wall, or a sphere touching it from above its equator,
// e.g. under an overhang): the contact normals balance gravity with forces >= -tol, the
// general form of the same criterion.
bool is_stable(const Packing &p, const DepositionDomain &d, std::size_t i, std::string &why)
{
  const Point a = centre(p, i);
  const double r = p.radius[i];
  if ((a.z - r) - d.z_floor <= kSupportTol * 2 * r) return true;
  const double lx = d.xhi - d.xlo, ly = d.yhi - d.ylo;
  std::vector<Support> sup;
  for (std::size_t j = 0; j < i; ++j) {
    const Point b = centre(p, j);
    const double dist = r + p.radius[j];
    for (int ix = d.periodic_x ? -1 : 0; ix <= (d.periodic_x ? 1 : 0); ++ix)
      for (int iy = d.periodic_y ? -1 : 0; iy <= (d.periodic_y ? 1 : 0); ++iy) {
        const double bx = b.x - ix * lx, by = b.y - iy * ly;
        const double dx = a.x - bx, dy = a.y - by, dz = a.z - b.z;
        if (std::sqrt(dx * dx + dy * dy + dz * dz) <= dist * (1 + kSupportTol))
          sup.push_back({false, bx, by, b.z, 0, 0});
      }
  }
  const double wtol = kSupportTol * 2 * r;
  if (!d.periodic_x && (a.x - r) - d.xlo <= wtol) sup.push_back({true, 0, 0, 0, 1, 0});
  if (!d.periodic_x && d.xhi - (a.x + r) <= wtol) sup.push_back({true, 0, 0, 0, -1, 0});
  if (!d.periodic_y && (a.y - r) - d.ylo <= wtol) sup.push_back({true, 0, 0, 0, 0, 1});
  if (!d.periodic_y && d.yhi - (a.y + r) <= wtol) sup.push_back({true, 0, 0, 0, 0, -1});
  const std::size_t m = sup.size();
  for (std::size_t u = 0; u < m; ++u)
    for (std::size_t v = u + 1; v < m; ++v)
      for (std::size_t w = v + 1; w < m; ++w) {
        const Support *s[3] = {&sup[u], &sup[v], &sup[w]};
        bool spheres_below = true;
        for (auto *q : s) spheres_below = spheres_below && !q->wall && q->z < a.z;
        if (spheres_below) {
          // Triangle test on the horizontal projections.
          const double ax = s[0]->x, ay = s[0]->y;
          const double bx = s[1]->x - ax, by = s[1]->y - ay;
          const double cx = s[2]->x - ax, cy = s[2]->y - ay;
          const double px = a.x - ax, py = a.y - ay;
          const double den = bx * cy - by * cx;
          if (std::fabs(den) < 1e-12 * (r * r)) continue;
          const double lb = (px * cy - py * cx) / den;
          const double lc = (bx * py - by * px) / den;
          const double la = 1.0 - lb - lc;
          if (la >= -kBalanceTol && lb >= -kBalanceTol && lc >= -kBalanceTol) return true;
        } else {
          double n[3][3];
          for (int q = 0; q < 3; ++q) {
            if (s[q]->wall) {
              n[q][0] = s[q]->nx;
              n[q][1] = s[q]->ny;
              n[q][2] = 0;
            } else {
              const double dx = a.x - s[q]->x, dy = a.y - s[q]->y, dz = a.z - s[q]->z;
              const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
              n[q][0] = dx / len;
              n[q][1] = dy / len;
              n[q][2] = dz / len;
            }
          }
          if (balances_gravity(n)) return true;
        }
      }
  why = "sphere " + std::to_string(i) + " at (" + std::to_string(a.x) + ", " +
        std::to_string(a.y) + ", " + std::to_string(a.z) + ") has " + std::to_string(m) +
        " supports and no stable triple";
  return false;
}

void expect_valid_packing(const Packing &p, const DepositionDomain &d, const std::string &label)
{
  EXPECT_LE(worst_overlap(p, d), kOverlapTol) << label;
  EXPECT_EQ(p.stats.unresolved, 0) << label;
  int unstable = 0;
  for (std::size_t i = 0; i < p.radius.size(); ++i) {
    std::string why;
    if (!is_stable(p, d, i, why)) {
      if (++unstable <= 3) ADD_FAILURE() << label << ": " << why;
    }
  }
  EXPECT_EQ(unstable, 0) << label;
  // Periodic directions: centres wrapped into [lo, hi).
  for (std::size_t i = 0; i < p.radius.size(); ++i) {
    const Point a = centre(p, i);
    if (d.periodic_x) {
      EXPECT_TRUE(a.x >= d.xlo && a.x < d.xhi) << label;
    }
    if (d.periodic_y) {
      EXPECT_TRUE(a.y >= d.ylo && a.y < d.yhi) << label;
    }
  }
}

// Exact stereology: volume of the spheres inside the slab z0 <= z <= z1, over the slab volume
// (integral of the disk areas pi (r^2 - (z - z_i)^2), a cubic in z). Periodic sides: every
// image's missing part is another image's present part, so whole spheres count.
double slab_packing_fraction(const Packing &p, const DepositionDomain &d, double z0, double z1)
{
  double volume = 0.0;
  for (std::size_t i = 0; i < p.radius.size(); ++i) {
    const double zc = p.xyz[3 * i + 2], r = p.radius[i];
    const double lo = std::max(z0, zc - r), hi = std::min(z1, zc + r);
    if (hi <= lo) continue;
    auto primitive = [&](double z) {
      const double u = z - zc;
      return r * r * u - u * u * u / 3.0;
    };
    volume += kPi * (primitive(hi) - primitive(lo));
  }
  return volume / ((d.xhi - d.xlo) * (d.yhi - d.ylo) * (z1 - z0));
}

// Bulk window: from 6R above the floor to 6R below the mean surface height, the surface height
// being 2 <z - z_floor> (a slab of uniform density filled from the floor has its centres' mean
// height at half its height).
void oracle_bulk_window(const Packing &p, const DepositionDomain &d, double radius, double &z0,
                 double &z1)
{
  double mean = 0.0;
  for (std::size_t i = 0; i < p.radius.size(); ++i) mean += p.xyz[3 * i + 2] - d.z_floor;
  mean /= static_cast<double>(p.radius.size());
  z0 = d.z_floor + 6.0 * radius;
  z1 = d.z_floor + 2.0 * mean - 6.0 * radius;
}

}  // namespace

// ---- analytic rests --------------------------------------------------------------------------

// A sphere dropped into the hollow of three touching spheres on the floor rests at the apex of
// the regular tetrahedron: centre above the triangle's centroid at height R + 2R sqrt(2/3).
TEST(Deposition, TetrahedralHollow)
{
  const double R = 1.0, cx = 5.0, cy = 5.0, circum = 2.0 * R / std::sqrt(3.0);
  for (int k = 0; k < 12; ++k) {  // several drop points around the centroid
    SequentialDeposition engine(make_domain(10, 10, true, true), R, 7);
    for (int q = 0; q < 3; ++q) {
      const double a = kPi / 2 + q * 2 * kPi / 3;
      engine.add_fixed_sphere(cx + circum * std::cos(a), cy + circum * std::sin(a), R, R);
    }
    const double off = 0.05 + 0.04 * k, ang = 0.5 * k;
    const auto o = engine.drop(cx + off * std::cos(ang), cy + off * std::sin(ang), R);
    EXPECT_EQ(o.rest, RestingOn::Supports);
    EXPECT_NEAR(o.x, cx, 1e-12);
    EXPECT_NEAR(o.y, cy, 1e-12);
    EXPECT_NEAR(o.z, R + 2 * R * std::sqrt(2.0 / 3.0), 1e-12);
  }
}

// Off-centre on a single floor sphere: the roll stays in the vertical plane through the drop
// point and the sphere's centre, then the fall ends on the floor in contact at distance 2R.
TEST(Deposition, RollsOffSingleSphereInDropPlane)
{
  SequentialDeposition engine(make_domain(10, 10, true, true), 1.0, 3);
  engine.add_fixed_sphere(5, 5, 1, 1);
  const auto o = engine.drop(5.3, 5.4, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 5 + 2 * 0.6, 1e-12);
  EXPECT_NEAR(o.y, 5 + 2 * 0.8, 1e-12);
  EXPECT_NEAR(o.z, 1.0, 1e-12);
}

// Exactly on top of a sphere (unstable equilibrium): leaves in a random direction keyed by the
// seed, reproducibly, and ends on the floor in contact.
TEST(Deposition, UnstableTopLeftInSeededRandomDirection)
{
  auto run = [](std::uint64_t seed) {
    SequentialDeposition engine(make_domain(10, 10, true, true), 1.0, seed);
    engine.add_fixed_sphere(5, 5, 1, 1);
    const auto o = engine.drop(5, 5, 1.0);
    EXPECT_EQ(o.rest, RestingOn::Floor);
    EXPECT_GE(engine.stats().perturbations, 1);
    EXPECT_NEAR(std::hypot(o.x - 5, o.y - 5), 2.0, 1e-12);
    EXPECT_NEAR(o.z, 1.0, 1e-12);
    return std::atan2(o.y - 5, o.x - 5);
  };
  EXPECT_EQ(run(11), run(11));
  EXPECT_NE(run(11), run(12));
}

// Between two touching floor spheres: roll on the first, then on both along their circle of
// common contact (plane x = 5, radius sqrt(3) R about their midpoint) down to the floor.
TEST(Deposition, RollsAlongGrooveOfTwoSpheres)
{
  SequentialDeposition engine(make_domain(10, 10, true, true), 1.0, 5);
  engine.add_fixed_sphere(4, 5, 1, 1);
  engine.add_fixed_sphere(6, 5, 1, 1);
  const auto o = engine.drop(5.2, 5.3, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 5.0, 1e-12);
  EXPECT_NEAR(o.y, 5.0 + std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(o.z, 1.0, 1e-12);
}

// FBC: rolling on a sphere towards a wall, then on the sphere and the wall (the circle of
// points touching both lies in the plane y = ylo + R) down to the floor.
TEST(Deposition, RollsAlongWall)
{
  SequentialDeposition engine(make_domain(10, 10, true, false), 1.0, 5);
  engine.add_fixed_sphere(5, 1.5, 1, 1);
  const auto o = engine.drop(5.2, 1.1, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 5.0 + std::sqrt(4.0 - 0.25), 1e-12);
  EXPECT_NEAR(o.y, 1.0, 1e-12);
  EXPECT_NEAR(o.z, 1.0, 1e-12);
}

// A sphere touching a wall, dropped in the wall plane: rolls in that plane (the wall is
// tangent all along the path, never an obstacle) to the floor.
TEST(Deposition, RollsInWallPlane)
{
  SequentialDeposition engine(make_domain(10, 10, true, false), 1.0, 5);
  engine.add_fixed_sphere(5, 1, 1, 1);
  const auto o = engine.drop(5.5, 1.0, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 7.0, 1e-12);
  EXPECT_NEAR(o.y, 1.0, 1e-12);
}

// A corner of two walls: a sphere rolling off a floor sphere near the corner is wedged by both
// walls and rests on three supports (two walls and the sphere) at (R, R, R + sqrt(4R^2 - 2a^2)).
TEST(Deposition, WedgedInCorner)
{
  SequentialDeposition engine(make_domain(10, 10, false, false), 1.0, 5);
  const double a = 0.3;
  engine.add_fixed_sphere(1 + a, 1 + a, 1, 1);
  const auto o = engine.drop(1.2, 1.1, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Supports);
  EXPECT_NEAR(o.x, 1.0, 1e-12);
  EXPECT_NEAR(o.y, 1.0, 1e-12);
  EXPECT_NEAR(o.z, 1.0 + std::sqrt(4.0 - 2 * a * a), 1e-12);
}

// A column exactly one diameter wide (four walls): a sphere dropped on the axis lands on top of
// the floor sphere. Every horizontal way off that unstable top enters a wall, so it is wedged
// there at rest (z = 3 R), on the first attempt; a stack of such spheres is a straight column.
TEST(Deposition, WedgedOnTopInColumnOneDiameterWide)
{
  SequentialDeposition engine(make_domain(2, 2, false, false), 1.0, 5);
  engine.add_fixed_sphere(1, 1, 1, 1);
  for (int k = 1; k <= 3; ++k) {
    const auto o = engine.drop(1, 1, 1.0);
    ASSERT_EQ(o.rest, RestingOn::Supports) << "sphere " << k;
    EXPECT_NEAR(o.x, 1.0, 1e-12);
    EXPECT_NEAR(o.y, 1.0, 1e-12);
    EXPECT_NEAR(o.z, 1.0 + 2.0 * k, 1e-12);
    engine.add_fixed_sphere(o.x, o.y, o.z, 1.0);
  }
  EXPECT_EQ(engine.stats().unresolved, 0);
  EXPECT_EQ(engine.stats().wedged, 3);
  EXPECT_EQ(engine.stats().perturbations, 0);
}

// A slot one diameter wide (walls at x = 0 and 2, periodic in y): on top of a floor sphere the
// only ways off run along the walls (+-y, a set of measure zero among horizontal directions); the
// sphere leaves along one of them and ends on the floor two radii from the sphere, touching it.
TEST(Deposition, LeavesTopAlongWallsOfSlotOneDiameterWide)
{
  auto run = [](std::uint64_t seed) {
    SequentialDeposition engine(make_domain(2, 10, false, true), 1.0, seed);
    engine.add_fixed_sphere(1, 5, 1, 1);
    const auto o = engine.drop(1, 5, 1.0);
    EXPECT_EQ(o.rest, RestingOn::Floor) << "seed " << seed;
    EXPECT_NEAR(o.x, 1.0, 1e-12);
    EXPECT_NEAR(std::fabs(o.y - 5.0), 2.0, 1e-12);
    EXPECT_NEAR(o.z, 1.0, 1e-12);
    return o.y > 5.0;
  };
  bool seen[2] = {false, false};
  for (std::uint64_t seed = 1; seed <= 16; ++seed) seen[run(seed) ? 1 : 0] = true;
  EXPECT_TRUE(seen[0] && seen[1]) << "both ways along the slot, by seed";
}

// Periodic images: a floor sphere near x = 0 is an obstacle to a drop near x = L.
TEST(Deposition, PeriodicImageIsAnObstacle)
{
  SequentialDeposition engine(make_domain(10, 10, true, true), 1.0, 5);
  engine.add_fixed_sphere(0.5, 5, 1, 1);
  const auto o = engine.drop(9.8, 5.0, 1.0);  // 0.7 from the image at x = 10.5
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 10.5 - 2.0, 1e-12);
  EXPECT_NEAR(o.y, 5.0, 1e-12);
}

// Every touching constraint counts, however many: a unit sphere falling onto the floor at (5, 5)
// meets at the same instant 12 fixed spheres of radius s = 0.05 resting on the floor on an arc
// around it (horizontal distance 2 sqrt(s), so |centre difference| = 1 + s at height 1). The
// floor is the 13th contact; the arc spans less than a half-turn, so no three small spheres
// balance the sphere and only the floor can hold it: it rests on the floor where it landed.
TEST(Deposition, ThirteenContactsAllCount)
{
  SequentialDeposition engine(make_domain(10, 10, true, true), 1.0, 5);
  const double s = 0.05, h = 2.0 * std::sqrt(s);
  const int n_small = 12;
  const double step = 150.0 / (n_small - 1) * kPi / 180.0;  // chord 2 h sin(step / 2) > 2 s
  for (int k = 0; k < n_small; ++k) {
    const double angle = -75.0 * kPi / 180.0 + k * step;
    engine.add_fixed_sphere(5 + h * std::cos(angle), 5 + h * std::sin(angle), s, s);
  }
  const auto o = engine.drop(5.0, 5.0, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  EXPECT_NEAR(o.x, 5.0, 1e-12);
  EXPECT_NEAR(o.y, 5.0, 1e-12);
  EXPECT_NEAR(o.z, 1.0, 1e-12);
  // The rest point touches all 12 small spheres (and the floor).
  for (std::size_t k = 0; k < engine.size() - 1; ++k) {
    const double *c = engine.centre(k);
    const double gap = std::sqrt((o.x - c[0]) * (o.x - c[0]) + (o.y - c[1]) * (o.y - c[1]) +
                                 (o.z - c[2]) * (o.z - c[2])) - (1.0 + s);
    EXPECT_NEAR(gap, 0.0, kSupportTol) << "small sphere " << k;
  }
}

// ---- brute-force oracles over many seeds -----------------------------------------------------

TEST(Deposition, NoOverlapAndStableOverSeeds)
{
  struct Case {
    const char *name;
    double lx, ly;
    bool px, py;
    RadiusDistribution radii;
  };
  const Case cases[] = {
      {"PBC mono", 8, 8, true, true, RadiusDistribution::monodisperse(1.0)},
      {"FBC mono", 8, 8, false, false, RadiusDistribution::monodisperse(1.0)},
      {"x periodic, y walls", 8, 6, true, false, RadiusDistribution::monodisperse(1.0)},
      {"PBC poly", 8, 8, true, true, RadiusDistribution::uniform(0.6, 1.0)},
      {"FBC poly", 7, 9, false, false, RadiusDistribution::uniform(0.5, 1.0)},
      {"PBC wide poly (radius ratio 3.3)", 8, 8, true, true,
       RadiusDistribution::uniform(0.3, 1.0)},
      {"narrow PBC (box of 2.5 diameters)", 5, 5, true, true,
       RadiusDistribution::monodisperse(1.0)},
  };
  for (const auto &c : cases)
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
      const auto d = make_domain(c.lx, c.ly, c.px, c.py);
      const Packing p = deposit_packing(300, c.radii, d, seed);
      ASSERT_EQ(p.radius.size(), 300u);
      for (double r : p.radius) {
        EXPECT_GE(r, c.radii.r_min);
        EXPECT_LE(r, c.radii.r_max);
      }
      expect_valid_packing(p, d, std::string(c.name) + " seed " + std::to_string(seed));
    }
}

// Columns (four walls) and slots (two walls, periodic along them) near the widths where spheres
// stack or jam against the walls: exactly one diameter D (each sphere wedged on top of the one
// below: the old kernel left those at the step cap), a hair above it, widths between D and 2 D
// where spheres zig-zag between the walls, and a hair either side of 2 D (two spheres side by
// side just fit): every sphere at rest, none overlapping, none left unresolved (a slot up to
// ~1e-5 D wider than D re-drops a few spheres: create_packing.rst).
TEST(Deposition, NarrowColumnsAndSlotsNearJammingWidths)
{
  const double widths[] = {2.0, 2.0 + 1e-9, 2.0 + 1e-6, 2.3, 3.0, 2.0 * std::sqrt(3.0),
                           4.0 - 1e-9, 4.0, 4.0 + 1e-9};
  for (const double w : widths)
    for (const bool slot : {false, true})
      for (const bool poly : {false, true})
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
          const auto d = make_domain(w, slot ? 8.0 : w, false, slot);
          const auto radii = poly ? RadiusDistribution::uniform(0.8, 1.0)
                                  : RadiusDistribution::monodisperse(1.0);
          const Packing p = deposit_packing(slot ? 120 : 40, radii, d, seed);
          expect_valid_packing(p, d, std::string(slot ? "slot" : "column") + " width " +
                                         std::to_string(w) + (poly ? " poly" : " mono") +
                                         " seed " + std::to_string(seed));
        }
}

TEST(Deposition, SameSeedSamePackingOtherSeedOther)
{
  const auto d = make_domain(10, 10, true, false);
  const Packing a = deposit_packing(500, RadiusDistribution::uniform(0.8, 1.0), d, 42);
  const Packing b = deposit_packing(500, RadiusDistribution::uniform(0.8, 1.0), d, 42);
  const Packing c = deposit_packing(500, RadiusDistribution::uniform(0.8, 1.0), d, 43);
  EXPECT_EQ(a.xyz, b.xyz);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_NE(a.xyz, c.xyz);
  // A prefix of a deposition is the deposition of fewer spheres (sphere i only sees 0..i-1).
  const Packing prefix = deposit_packing(200, RadiusDistribution::uniform(0.8, 1.0), d, 42);
  EXPECT_TRUE(std::equal(prefix.xyz.begin(), prefix.xyz.end(), a.xyz.begin()));
}

// A wide box of few spheres gets columns wider than a diameter (at most kGridCellsPerSphere per
// sphere): the grid no longer grows with the box's area, and the spheres land where they did
// on the grid of one-diameter columns.
TEST(Deposition, WideSparseBoxBoundsTheColumnsNotThePacking)
{
  namespace dd = tapmc::deposition_detail;
  const auto wide = make_domain(20000, 20000, true, true);
  dd::LayeredGrid grid;
  grid.setup(wide, 1.0, 16 * 10 + 4096);
  EXPECT_LE(static_cast<long>(grid.columns_x()) * grid.columns_y(), 16 * 10 + 4096);
  EXPECT_GE(grid.columns_x(), 1);
  EXPECT_LE(grid.columns_x(), 20000 / 1);
  // One diameter wide and a million long: the long axis alone takes the cap.
  grid.setup(make_domain(1.0, 1e6, false, true), 1.0, 3000);
  EXPECT_EQ(grid.columns_x(), 1);
  EXPECT_EQ(grid.columns_y(), 3000);
  // Without a sphere count: kGridMaxCellsPerSideAxis per axis.
  grid.setup(wide, 1.0, 1L << 40);
  EXPECT_EQ(grid.columns_x(), tapmc::defaults::kGridMaxCellsPerSideAxis);

  // A pile dropped on one spot of a box 300 diameters wide: 90 000 one-diameter columns
  // against 66 x 66 wider ones (20 spheres announced): the same pile, to rounding. (The grids
  // find a sphere's contacts in another order, so its support forces differ by ~1e-16; an
  // unstable top amplifies that: here at drop 264 of a longer pile, two floor positions
  // 1.7 apart. Hence 150 drops.)
  const auto d = make_domain(300, 300, true, false);
  SequentialDeposition fine(d, 0.5, 7), coarse(d, 0.5, 7, 20);
  std::uint64_t state = 12345;
  for (int i = 0; i < 150; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double v = static_cast<double>(state >> 11) * 0x1.0p-53;
    const double x = 147.0 + 6.0 * u, y = 147.0 + 6.0 * v;
    const auto a = fine.drop(x, y, 0.5);
    const auto b = coarse.drop(x, y, 0.5);
    ASSERT_EQ(a.rest, b.rest) << "drop " << i;

  }
  ASSERT_EQ(fine.size(), coarse.size());
  double worst = 0.0, top = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      worst = std::max(worst, std::fabs(fine.centre(i)[k] - coarse.centre(i)[k]));
      if (k == 2) top = std::max(top, fine.centre(i)[k]);
    }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(top, 3.0) << "the drops must pile up, not land side by side";

  // deposit_packing announces its N: 50 spheres on the floor of a box 3000 diameters wide.
  const auto sparse = make_domain(3000, 3000, true, false);
  const Packing p = deposit_packing(50, RadiusDistribution::monodisperse(0.5), sparse, 3);
  expect_valid_packing(p, sparse, "50 spheres, box of 3000 diameters");
}

// ---- bad input -------------------------------------------------------------------------------

namespace {
template <class Ex, class F> std::string message_of(F &&f)
{
  try {
    f();
  } catch (const Ex &e) {
    return e.what();
  }
  return "(no exception)";
}
}  // namespace

TEST(Deposition, BadInputNamesTheArgument)
{
  const auto d = make_domain(10, 10, true, true);
  const auto mono = RadiusDistribution::monodisperse(1.0);
  EXPECT_NE(message_of<std::invalid_argument>([&] { deposit_packing(-1, mono, d, 1); })
                .find("n = -1"),
            std::string::npos);
  EXPECT_NE(message_of<std::invalid_argument>([&] {
              deposit_packing(10, RadiusDistribution::monodisperse(0.0), d, 1);
            }).find("r_min"),
            std::string::npos);
  EXPECT_NE(message_of<std::invalid_argument>([&] {
              deposit_packing(10, RadiusDistribution::uniform(1.0, 0.5), d, 1);
            }).find("r_max"),
            std::string::npos);
  EXPECT_NE(message_of<std::invalid_argument>([&] {
              deposit_packing(10, mono, make_domain(1.5, 10, false, true), 1);
            }).find("x extent"),
            std::string::npos);
  EXPECT_NE(message_of<std::invalid_argument>([&] {
              deposit_packing(10, mono, make_domain(10, 1.9, true, true), 1);
            }).find("y extent"),
            std::string::npos);
  auto low = d;
  low.z_top = 3.0;  // room for about one layer only
  EXPECT_NE(message_of<std::runtime_error>([&] { deposit_packing(200, mono, low, 1); })
                .find("z_top"),
            std::string::npos);
  SequentialDeposition engine(make_domain(10, 10, false, false), 1.0, 1);
  EXPECT_NE(message_of<std::invalid_argument>([&] { engine.drop(0.5, 5, 1.0); }).find("x = "),
            std::string::npos);
  EXPECT_NE(message_of<std::invalid_argument>([&] { engine.drop(5, 5, 2.0); }).find("radius"),
            std::string::npos);
  EXPECT_EQ(deposit_packing(0, mono, d, 1).radius.size(), 0u);
}

// create_packing's parameters: each bad one is named with its value and its range; the radii
// span [R (1 - W), R (1 + W)].
TEST(Deposition, PackingParamsValidation)
{
  tapmc::PackingParams good;
  good.n = 10;
  good.radius = 2.0;
  good.dispersity = 0.25;
  EXPECT_NO_THROW(tapmc::validate(good));
  EXPECT_EQ(good.radii().r_min, 1.5);
  EXPECT_EQ(good.radii().r_max, 2.5);
  auto message = [&](auto change) {
    tapmc::PackingParams p = good;
    change(p);
    return message_of<std::invalid_argument>([&] { tapmc::validate(p); });
  };
  EXPECT_EQ(message([](auto &p) { p.n = 0; }),
            "N = 0 is outside the allowed range [1, 2^31 - 2] (a number of spheres)");
  EXPECT_EQ(message([](auto &p) { p.n = 2147483647; }),
            "N = 2147483647 is outside the allowed range [1, 2^31 - 2] "
            "(a number of spheres)");
  EXPECT_EQ(message([](auto &p) { p.radius = -0.5; }),
            "R = -0.5 is outside the allowed range (0, +inf) (the mean sphere radius)");
  EXPECT_EQ(message([](auto &p) { p.radius = INFINITY; }),
            "R = inf is outside the allowed range (0, +inf) (the mean sphere radius)");
  EXPECT_EQ(message([](auto &p) { p.dispersity = 1.0; }),
            "dispersity = 1 is outside the allowed range [0, 1) "
            "(radii uniform in [R(1 - W), R(1 + W)])");
  EXPECT_EQ(message([](auto &p) { p.density = 0.0; }),
            "density = 0 is outside the allowed range (0, +inf)");
}

// ---- the paper's initial packing: N = 4096, L = 32R, PBC -------------------------------------

// Bulk packing fraction over 5 seeds (literature value of this algorithm about 0.58; the
// paper's initial PBC packing 0.584), and the full oracles on one of them.
TEST(Deposition, BulkPackingFractionN4096)
{
  const auto d = make_domain(32, 32, true, true);
  const auto mono = RadiusDistribution::monodisperse(1.0);
  std::vector<double> phis;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Packing p = deposit_packing(4096, mono, d, seed);
    double z0, z1;
    oracle_bulk_window(p, d, 1.0, z0, z1);
    ASSERT_GT(z1 - z0, 10.0);  // a real bulk slab (about 17R here)
    const double phi = slab_packing_fraction(p, d, z0, z1);
    // The stereology kernel (create_packing's report) agrees with the oracle.
    const tapmc::stereo::Spheres spheres{p.xyz.data(), p.radius.data(), 0.0, nullptr,
                                         static_cast<int>(p.radius.size())};
    EXPECT_NEAR(tapmc::stereo::horizontal_slab_volume(spheres, z0, z1) /
                    ((d.xhi - d.xlo) * (d.yhi - d.ylo) * (z1 - z0)),
                phi, 1e-12);
    EXPECT_GE(phi, 0.56) << "seed " << seed;
    EXPECT_LE(phi, 0.61) << "seed " << seed;
    phis.push_back(phi);
    if (seed == 1) expect_valid_packing(p, d, "N=4096 PBC seed 1");
  }
  double mean = 0.0, var = 0.0;
  for (double v : phis) mean += v / phis.size();
  for (double v : phis) var += (v - mean) * (v - mean) / (phis.size() - 1);
  std::printf("[ phi_bulk ] N=4096 L=32R PBC, 5 seeds: mean %.4f, std %.4f, min %.4f, max %.4f\n",
              mean, std::sqrt(var), *std::min_element(phis.begin(), phis.end()),
              *std::max_element(phis.begin(), phis.end()));
  EXPECT_GE(mean, 0.56);
  EXPECT_LE(mean, 0.61);
}

// FBC with the same size: no overlap, every sphere stable (walls as supports).
TEST(Deposition, ValidPackingN4096Walls)
{
  const auto d = make_domain(32, 32, false, false);
  const Packing p = deposit_packing(4096, RadiusDistribution::monodisperse(1.0), d, 9);
  expect_valid_packing(p, d, "N=4096 FBC seed 9");
}

