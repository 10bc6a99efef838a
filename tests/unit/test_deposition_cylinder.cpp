// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the sequential deposition in a vertical cylindrical container: analytic rests against
// the curved wall, brute-force overlap and stability oracles on packings in tubes, and the box
// paths left unchanged by the cylinder's code (a checksum of packings made before it existed).
#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_math.h"
#include "tapmc_stereology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
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
// Support forces accepted down to -kBalanceTol (gravity = 1); a two-support balance may miss
// e_z by kResidualTol.
constexpr double kBalanceTol = 1e-9;
constexpr double kResidualTol = 1e-8;

// A tube of radius rc about (0, 0) in the box [-half, half]^2 (half >= rc), floor at z = 0.
DepositionDomain tube(double rc, double half)
{
  DepositionDomain d;
  d.xlo = d.ylo = -half;
  d.xhi = d.yhi = half;
  d.periodic_x = d.periodic_y = false;
  d.has_cylinder = true;
  d.cylinder = {0.0, 0.0, rc};
  return d;
}
DepositionDomain tube(double rc) { return tube(rc, rc); }

// ---- independent oracles (no code shared with the kernel) -----------------------------------

struct P3 {
  double x, y, z;
};
P3 centre(const Packing &p, std::size_t i)
{
  return {p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]};
}
double axis_dist(const P3 &a, const DepositionDomain &d)
{
  return std::hypot(a.x - d.cylinder.cx, a.y - d.cylinder.cy);
}

// Largest relative overlap over all pairs (brute force), the floor and the cylinder wall
// (penetration over the contact distance, or over the diameter for floor and wall).
double worst_overlap(const Packing &p, const DepositionDomain &d)
{
  double worst = -1.0;
  const std::size_t n = p.radius.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P3 a = centre(p, i);
    const double ra = p.radius[i];
    worst = std::max(worst, (d.z_floor - (a.z - ra)) / (2 * ra));
    worst = std::max(worst, (axis_dist(a, d) + ra - d.cylinder.radius) / (2 * ra));
    for (std::size_t j = 0; j < i; ++j) {
      const P3 b = centre(p, j);
      const double dist = ra + p.radius[j];
      const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < dist * dist) worst = std::max(worst, (dist - std::sqrt(r2)) / dist);
    }
  }
  return worst;
}

double det3(const double a[3], const double b[3], const double c[3])
{
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// Sphere i is stable: on the floor; or three supports (earlier spheres it touches, the wall)
// whose unit normals balance gravity with forces >= -tol; or two supports (the deposition's
// rest against the curved wall) whose normals span e_z with forces >= -tol.
bool is_stable(const Packing &p, const DepositionDomain &d, std::size_t i, std::string &why)
{
  const P3 a = centre(p, i);
  const double r = p.radius[i];
  if ((a.z - r) - d.z_floor <= kSupportTol * 2 * r) return true;
  std::vector<std::array<double, 3>> normals;
  for (std::size_t j = 0; j < i; ++j) {
    const P3 b = centre(p, j);
    const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (len <= (r + p.radius[j]) * (1 + kSupportTol))
      normals.push_back({dx / len, dy / len, dz / len});
  }
  const double h = axis_dist(a, d);
  if ((d.cylinder.radius - r) - h <= kSupportTol * 2 * r)
    normals.push_back({-(a.x - d.cylinder.cx) / h, -(a.y - d.cylinder.cy) / h, 0.0});
  const std::size_t m = normals.size();
  const double ez[3] = {0, 0, 1};
  for (std::size_t u = 0; u < m; ++u)
    for (std::size_t v = u + 1; v < m; ++v) {
      // two supports: least squares mu_u n_u + mu_v n_v = e_z, exact residual
      const double *nu = normals[u].data(), *nv = normals[v].data();
      const double c = nu[0] * nv[0] + nu[1] * nv[1] + nu[2] * nv[2];
      const double den = 1 - c * c;
      if (den > 1e-12) {
        const double mu_u = (nu[2] - c * nv[2]) / den, mu_v = (nv[2] - c * nu[2]) / den;
        double res = 0;
        for (int q = 0; q < 3; ++q) {
          const double e = mu_u * nu[q] + mu_v * nv[q] - ez[q];
          res += e * e;
        }
        if (std::sqrt(res) <= kResidualTol && mu_u >= -kBalanceTol && mu_v >= -kBalanceTol)
          return true;
      }
      for (std::size_t w = v + 1; w < m; ++w) {
        const double *nw = normals[w].data();
        const double det = det3(nu, nv, nw);
        if (std::fabs(det) < 1e-12) continue;
        const double m0 = det3(ez, nv, nw) / det, m1 = det3(nu, ez, nw) / det,
                     m2 = det3(nu, nv, ez) / det;
        if (m0 >= -kBalanceTol && m1 >= -kBalanceTol && m2 >= -kBalanceTol) return true;
      }
    }
  why = "sphere " + std::to_string(i) + " at (" + std::to_string(a.x) + ", " +
        std::to_string(a.y) + ", " + std::to_string(a.z) + ") has " + std::to_string(m) +
        " supports and no stable pair or triple";
  return false;
}

void expect_valid_tube_packing(const Packing &p, const DepositionDomain &d, std::size_t n,
                               const std::string &label)
{
  ASSERT_EQ(p.radius.size(), n) << label;
  ASSERT_EQ(p.xyz.size(), 3 * n) << label;
  EXPECT_LE(worst_overlap(p, d), kOverlapTol) << label;
  EXPECT_EQ(p.stats.unresolved, 0) << label;
  int unstable = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::string why;
    if (!is_stable(p, d, i, why) && ++unstable <= 3) ADD_FAILURE() << label << ": " << why;
  }
  EXPECT_EQ(unstable, 0) << label;
}

// FNV-1a over the bytes of the centres and radii: a bitwise fingerprint of a packing.
std::uint64_t fingerprint(const Packing &p)
{
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void *data, std::size_t n) {
    const auto *b = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= b[i];
      h *= 1099511628211ull;
    }
  };
  mix(p.xyz.data(), p.xyz.size() * sizeof(double));
  mix(p.radius.data(), p.radius.size() * sizeof(double));
  return h;
}

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

// ---- analytic rests against the curved wall ---------------------------------------------------

// A floor sphere j touching the wall at azimuth 0 (centre (4, 0, 1) in a tube of radius 5): a
// sphere dropped against the wall beside it lands on j, rolls on j along the wall away from it
// (the sphere-cylinder path) until level with j's centre, and drops there onto the floor,
// touching j and the wall: at the azimuth where the chord 8 sin(psi / 2) is 2.
TEST(DepositionCylinder, RollsAlongWallOffSphereToFloor)
{
  for (double a0 : {0.1, 0.2, -0.15}) {
    SequentialDeposition e(tube(5.0), 1.0, 3);
    e.add_fixed_sphere(4, 0, 1, 1);
    const auto o = e.drop(4 * std::cos(a0), 4 * std::sin(a0), 1.0);
    const double psi = std::copysign(2 * std::asin(0.25), a0);
    EXPECT_EQ(o.rest, RestingOn::Floor) << a0;
    EXPECT_NEAR(o.x, 4 * std::cos(psi), 1e-12) << a0;
    EXPECT_NEAR(o.y, 4 * std::sin(psi), 1e-12) << a0;
    EXPECT_NEAR(o.z, 1.0, 1e-12) << a0;
    EXPECT_GE(e.stats().wall_rolls, 1) << a0;
  }
}

// Two floor spheres against the wall at azimuths 0 and alpha (chord 2.2: 0.2 apart): a sphere
// dropped against the wall near the first rolls along the wall towards the second and rests on
// both and the wall, midway, at height 1 + sqrt(4 - h^2), h = 8 sin(alpha / 4).
TEST(DepositionCylinder, RestsOnTwoSpheresAndWall)
{
  const double alpha = 2 * std::asin(0.275);
  for (double f : {0.15, 0.25, 0.35}) {
    SequentialDeposition engine(tube(5.0), 1.0, 3);
    engine.add_fixed_sphere(4, 0, 1, 1);
    engine.add_fixed_sphere(4 * std::cos(alpha), 4 * std::sin(alpha), 1, 1);
    const auto o = engine.drop(4 * std::cos(f * alpha), 4 * std::sin(f * alpha), 1.0);
    const double h = 8 * std::sin(alpha / 4);
    EXPECT_EQ(o.rest, RestingOn::Supports) << f;
    EXPECT_NEAR(o.x, 4 * std::cos(alpha / 2), 1e-12) << f;
    EXPECT_NEAR(o.y, 4 * std::sin(alpha / 2), 1e-12) << f;
    EXPECT_NEAR(o.z, 1 + std::sqrt(4 - h * h), 1e-12) << f;
  }
}

// A tube narrower than two diameters (radius 1.8, R = 1) with a floor sphere against the wall at
// (0.8, 0, 1): a sphere dropped near the axis lands on it, rolls on it into the wall, then along
// the wall to the lowest point of that path, on the far side of the axis, where it rests on the
// sphere and the wall alone: (-0.8, 0, 1 + sqrt(4 - 1.6^2)) = (-0.8, 0, 2.2).
TEST(DepositionCylinder, RestsOnOneSphereAndWallInNarrowTube)
{
  for (double y0 : {0.0, 0.1, -0.3, 0.5}) {
    SequentialDeposition engine(tube(1.8), 1.0, 3);
    engine.add_fixed_sphere(0.8, 0, 1, 1);
    const auto o = engine.drop(0.0, y0, 1.0);
    EXPECT_EQ(o.rest, RestingOn::Supports) << y0;
    EXPECT_NEAR(o.x, -0.8, 1e-12) << y0;
    EXPECT_NEAR(o.y, 0.0, 1e-12) << y0;
    EXPECT_NEAR(o.z, 2.2, 1e-12) << y0;
  }
}

// On the axis of that tube: the first sphere rests on the floor at the axis; the second, dropped
// on the axis, is exactly on top of it (left in a seeded random direction) and rolls into the
// wall, where it rests on the first sphere and the wall (a level path: the first is on the axis)
// at distance 0.8 from the axis and height 1 + sqrt(4 - 0.8^2).
TEST(DepositionCylinder, OnAxisOfNarrowTubeEndsOnSphereAndWall)
{
  for (std::uint64_t seed : {1, 2, 3}) {
    SequentialDeposition engine(tube(1.8), 1.0, seed);
    const auto first = engine.drop(0.0, 0.0, 1.0);
    EXPECT_EQ(first.rest, RestingOn::Floor);
    const auto o = engine.drop(0.0, 0.0, 1.0);
    EXPECT_EQ(o.rest, RestingOn::Supports);
    EXPECT_GE(engine.stats().perturbations, 1);
    EXPECT_NEAR(std::hypot(o.x, o.y), 0.8, 1e-12);
    EXPECT_NEAR(o.z, 1 + std::sqrt(4 - 0.64), 1e-12);
  }
}

// A roll on one sphere (a vertical great circle) meets the curved wall: the contact event of the
// circle with the wall, then the roll along the wall ends on the floor. Sphere j at (3, 0, 1) in a
// tube of radius 5 (1 from the wall); a drop at (3.5, 0.2) rolls outwards on j towards the wall.
TEST(DepositionCylinder, GreatCircleRollMeetsWall)
{
  SequentialDeposition engine(tube(5.0), 1.0, 3);
  engine.add_fixed_sphere(3, 0, 1, 1);
  const auto o = engine.drop(3.5, 0.2, 1.0);
  EXPECT_EQ(o.rest, RestingOn::Floor);
  // on the floor, touching j and the wall: |p_xy| = 4 and |p_xy - (3, 0)| = 2
  EXPECT_NEAR(std::hypot(o.x, o.y), 4.0, 1e-12);
  EXPECT_NEAR(std::hypot(o.x - 3, o.y), 2.0, 1e-12);
  EXPECT_GT(o.y, 0.0);
  EXPECT_NEAR(o.z, 1.0, 1e-12);
}

// ---- validation ------------------------------------------------------------------------------

TEST(DepositionCylinder, BadContainerNamesTheArgument)
{
  auto message = [](DepositionDomain d, double r_max = 1.0) {
    return message_of<std::invalid_argument>([&] { SequentialDeposition e(d, r_max, 1); });
  };
  DepositionDomain d = tube(5.0);
  d.periodic_x = true;
  EXPECT_EQ(message(d), "periodic_x = true is outside the allowed range {false} (a cylindrical "
                        "container needs walls in x and y)");
  d = tube(5.0);
  d.periodic_y = true;
  EXPECT_NE(message(d).find("periodic_y = true"), std::string::npos);
  EXPECT_EQ(message(tube(0.9, 5.0)), "cylinder radius = 0.9 is outside the allowed range (R_max, "
                                     "+inf) = (1, +inf) (the container must be wider than its "
                                     "largest sphere)");
  EXPECT_EQ(message(tube(6.0, 5.0)),
            "cylinder radius = 6 is outside the allowed range (max_radius, min(xhi - xlo, yhi - "
            "ylo) / 2] = (1, 5] (the disk must lie inside the box)");
  d = tube(4.0, 5.0);
  d.cylinder.cx = 1.5;
  EXPECT_EQ(message(d), "cylinder cx = 1.5 is outside the allowed range [xlo + radius, xhi - "
                        "radius] = [-1, 1] (the disk must lie inside the box)");
  d = tube(4.0, 5.0);
  d.cylinder.cy = -2;
  EXPECT_NE(message(d).find("cylinder cy = -2"), std::string::npos);
  d = tube(4.0, 5.0);
  d.cylinder.cx = NAN;
  EXPECT_NE(message(d).find("cylinder cx = nan"), std::string::npos);
  SequentialDeposition engine(tube(5.0), 1.0, 1);
  EXPECT_NE(message_of<std::invalid_argument>([&] { engine.drop(3.0, 3.0, 1.0); })
                .find("drop point distance from the cylinder axis"),
            std::string::npos);
  EXPECT_NO_THROW(engine.drop(0.0, 4.0, 1.0));
}

// ---- packings in tubes: brute-force oracles -----------------------------------------------------

// Small tubes over seeds: monodisperse, polydisperse (spheres both smaller and larger than their
// supports: the wall's support may vanish near a smaller one), narrower than two diameters
// (rests on one sphere and the wall), off-centre axis in a larger box.
TEST(DepositionCylinder, NoOverlapAndStableOverSeeds)
{
  struct Case {
    const char *name;
    DepositionDomain d;
    RadiusDistribution radii;
    int n;
  };
  DepositionDomain off = tube(3.5, 6.0);
  off.cylinder.cx = 1.5;
  off.cylinder.cy = -2.0;
  off.z_floor = -3.0;
  const Case cases[] = {
      {"tube 4 mono", tube(4.0), RadiusDistribution::monodisperse(1.0), 300},
      {"tube 4 poly", tube(4.0), RadiusDistribution::uniform(0.5, 1.0), 300},
      {"tube 1.8 (narrower than 2 diameters)", tube(1.8), RadiusDistribution::monodisperse(1.0),
       100},
      {"tube 1.2 (a column)", tube(1.2), RadiusDistribution::monodisperse(1.0), 60},
      {"off-centre tube, poly", off, RadiusDistribution::uniform(0.6, 1.0), 300},
  };
  for (const auto &c : cases)
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const Packing p = deposit_packing(c.n, c.radii, c.d, seed);
      expect_valid_tube_packing(p, c.d, c.n, std::string(c.name) + " seed " + std::to_string(seed));
    }
}

// The Knight / Nowak aspect ratio: a tube 10 bead diameters wide (radius 10 R), N = 3000; the
// full oracles, determinism, the wall contacts, and the packing fractions of the core
// (r < R_c - 7R) and of the whole tube in the bulk window.
TEST(DepositionCylinder, TubeOfTenDiametersN3000)
{
  const DepositionDomain d = tube(10.0);
  const auto mono = RadiusDistribution::monodisperse(1.0);
  const int n = 3000;
  const auto t0 = std::chrono::steady_clock::now();
  const Packing p = deposit_packing(n, mono, d, 17);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  expect_valid_tube_packing(p, d, n, "tube R_c = 10R N = 3000 seed 17");
  const Packing again = deposit_packing(n, mono, d, 17);
  EXPECT_EQ(fingerprint(p), fingerprint(again));
  EXPECT_NE(fingerprint(p), fingerprint(deposit_packing(200, mono, d, 18)));
  // a prefix of a deposition is the deposition of fewer spheres
  const Packing prefix = deposit_packing(500, mono, d, 17);
  EXPECT_TRUE(std::equal(prefix.xyz.begin(), prefix.xyz.end(), p.xyz.begin()));

  const auto wall = tapmc::cylinder_wall_contacts(p, d);
  ASSERT_EQ(wall.size(), static_cast<std::size_t>(n));
  int on_wall = 0;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    const double gap = (d.cylinder.radius - 1.0) - axis_dist(centre(p, i), d);
    EXPECT_EQ(wall[i] != 0, gap <= kSupportTol * 2.0) << i;
    on_wall += wall[i];
  }
  EXPECT_GT(on_wall, n / 10);  // the wall holds a good part of the outer layer

  double z0, z1;
  tapmc::bulk_window(p, d, 6.0, z0, z1);
  ASSERT_GT(z1 - z0, 20.0);
  const tapmc::stereo::Spheres spheres{p.xyz.data(), p.radius.data(), 0.0, nullptr, n};
  const double phi_tube = tapmc::stereo::cylinder_slab_volume(spheres, d.cylinder, z0, z1) /
                          (kPi * d.cylinder.radius * d.cylinder.radius * (z1 - z0));
  const auto zones = tapmc::stereo::cylinder_zones(spheres, d.cylinder, 7.0, z0, z1);
  std::printf("[ phi_tube ] N=%d R_c=10R seed 17: whole tube %.4f, core (r < R_c - 7R) %.4f, "
              "wall zone %.4f; %d of %d spheres touch the wall; %lld wall rolls, %lld segments, "
              "%lld redrops; %.3f s (%.1f us per sphere)\n",
              n, phi_tube, zones.phi_core, zones.phi_wall, on_wall, n,
              static_cast<long long>(p.stats.wall_rolls), static_cast<long long>(p.stats.segments),
              static_cast<long long>(p.stats.redrops), seconds, seconds / n * 1e6);
  EXPECT_GE(zones.phi_core, 0.53);
  EXPECT_LE(zones.phi_core, 0.63);
  EXPECT_GE(phi_tube, 0.50);
  EXPECT_LE(phi_tube, 0.62);
  EXPECT_GT(p.stats.wall_rolls, 0);
}

// Polydisperse, same tube, another seed: the full oracles.
TEST(DepositionCylinder, TubeOfTenDiametersPolydisperse)
{
  const DepositionDomain d = tube(10.0);
  const Packing p = deposit_packing(2000, RadiusDistribution::uniform(0.7, 1.0), d, 5);
  expect_valid_tube_packing(p, d, 2000, "tube R_c = 10 poly N = 2000 seed 5");
}

// ---- the box paths are unchanged --------------------------------------------------------------

// Fingerprints of packings in boxes (PBC mono 16 x 16, FBC poly 12 x 10, x periodic / y walls
// 10 x 10; 600 spheres each) computed with the deposition kernel as it was before the cylinder
// was added (commit eff2ab2): a small program called deposit_packing with these arguments and
// printed fingerprint() of each result. The cylinder's code must leave every box path bit for
// bit. The arithmetic is IEEE double without fused multiply-add (the portable x86-64 build); a
// build that contracts a * b + c into one rounding (-march=native with FMA, or an ARM build)
// rounds differently, so the check is skipped there.
TEST(DepositionCylinder, BoxPackingsUnchangedBitForBit)
{
#if defined(__FMA__) || !(defined(__x86_64__) || defined(_M_X64))
  GTEST_SKIP() << "reference fingerprints are of the portable x86-64 build (no FMA contraction)";
#endif
  struct Case {
    double lx, ly;
    bool px, py;
    double r_min, r_max;
    std::uint64_t seed, expected;
  };
  const Case cases[] = {
      {16, 16, true, true, 1.0, 1.0, 42, 0xc52eb21090b392b3ull},
      {12, 10, false, false, 0.7, 1.0, 7, 0xfb858e75951764eaull},
      {10, 10, true, false, 1.0, 1.0, 3, 0x737e001e4c084d5eull},
  };
  for (const auto &c : cases) {
    DepositionDomain d;
    d.xhi = c.lx;
    d.yhi = c.ly;
    d.periodic_x = c.px;
    d.periodic_y = c.py;
    const Packing p =
        deposit_packing(600, RadiusDistribution::uniform(c.r_min, c.r_max), d, c.seed);
    EXPECT_EQ(fingerprint(p), c.expected) << c.lx << " x " << c.ly << " seed " << c.seed;
    EXPECT_EQ(p.stats.wall_rolls, 0);
  }
}
