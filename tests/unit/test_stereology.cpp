// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Unit tests of the exact stereology kernel: analytic spheres and lattices, quadrature oracles.
#include "tapmc_stereology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

using namespace tapmc::stereo;

namespace {

const double kPi = std::acos(-1.0);
const double kFccFraction = kPi / (3.0 * std::sqrt(2.0));
const double kSimpleCubicFraction = kPi / 6.0;

// Tanh-sinh (double exponential) quadrature: exact to ~1e-15 for integrands that are analytic
// inside [a, b], even with algebraic singularities at the ends (sqrt-type chord lengths).
double tanh_sinh(const std::function<double(double)> &f, double a, double b)
{
  if (!(a < b)) return 0.0;
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const double h = 1.0 / 64.0;
  double sum = 0.0;
  for (int k = -256; k <= 256; ++k) {  // t in [-4, 4]
    const double t = k * h;
    const double u = 0.5 * kPi * std::sinh(t);
    const double ch = std::cosh(u);
    const double x = std::tanh(u);
    const double w = 0.5 * kPi * std::cosh(t) / (ch * ch);
    if (w < 1e-300 || std::fabs(x) >= 1.0) continue;
    sum += w * f(mid + half * x);
  }
  return sum * h * half;
}

// Integrate f over [a, b] split at the given break points (where f is not smooth).
double piecewise_tanh_sinh(const std::function<double(double)> &f, double a, double b,
                           std::vector<double> breaks)
{
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  double total = 0.0;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    if (lo < hi) total += tanh_sinh(f, lo, hi);
  }
  return total;
}

struct Packing {
  std::vector<double> xyz;
  std::vector<double> radius;
  Spheres view(double uniform = 0.0) const
  {
    Spheres s;
    s.xyz = xyz.data();
    s.count = static_cast<int>(xyz.size() / 3);
    if (uniform > 0.0)
      s.uniform_radius = uniform;
    else
      s.radius = radius.data();
    return s;
  }
  void add(double x, double y, double z, double r)
  {
    xyz.insert(xyz.end(), {x, y, z});
    radius.push_back(r);
  }
};

// FCC with cubic cell a, spheres at contact (R = a / (2 sqrt 2)), n x n x m cells from origin.
Packing fcc(double a, int n, int m)
{
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  const double r = a / (2.0 * std::sqrt(2.0));
  Packing p;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto &b : basis) p.add((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a, r);
  return p;
}

Packing simple_cubic(double a, int n, int m)
{
  Packing p;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.add(i * a, j * a, k * a, 0.5 * a);
  return p;
}

Box make_box(double lx, double ly, double zlo, double zhi, bool periodic)
{
  Box b;
  b.lo[0] = 0.0;
  b.lo[1] = 0.0;
  b.lo[2] = zlo;
  b.hi[0] = lx;
  b.hi[1] = ly;
  b.hi[2] = zhi;
  b.periodic[0] = b.periodic[1] = periodic;
  return b;
}

// Random polydisperse spheres, centres inside [0, L]^2 x [0, H].
Packing random_spheres(unsigned seed, int count, double length, double height)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, length), uz(0.0, height), ur(0.3, 1.2);
  Packing p;
  for (int i = 0; i < count; ++i) p.add(ux(rng), ux(rng), uz(rng), ur(rng));
  return p;
}

double cap_volume(double r, double h)  // cap of height h of a sphere of radius r
{
  return kPi * h * h * (3.0 * r - h) / 3.0;
}

}  // namespace

// ---- one sphere ------------------------------------------------------------------------------

TEST(StereologySphere, HorizontalCutIsTheDiskArea)
{
  Packing p;
  p.add(1.3, 2.1, 5.0, 0.8);
  const Spheres s = p.view();
  for (double u : {-0.79, -0.5, 0.0, 0.3, 0.7999}) {
    EXPECT_NEAR(horizontal_cut_area(s, 5.0 + u), kPi * (0.64 - u * u), 1e-14) << u;
  }
  EXPECT_EQ(horizontal_cut_area(s, 5.0 + 0.81), 0.0);
  EXPECT_EQ(horizontal_cut_area(s, 5.0 - 0.81), 0.0);
}

TEST(StereologySphere, SlabHoldingTheSphereGivesItsVolume)
{
  Packing p;
  p.add(1.3, 2.1, 5.0, 0.8);
  const Box box = make_box(4.0, 4.0, 0.0, 10.0, true);
  const double slab = horizontal_slab_volume(p.view(), 3.0, 7.5);
  EXPECT_NEAR(slab, 4.0 / 3.0 * kPi * 0.512, 1e-14);
  // as a packing fraction: sphere volume / (L^2 h)
  const Summary sum = [&] {
    SummarySettings set;
    set.floor = 3.0;
    set.bulk_height = 4.5;
    return summarize(p.view(), box, set);
  }();
  EXPECT_NEAR(sum.phi_bulk, 4.0 / 3.0 * kPi * 0.512 / (16.0 * 4.5), 1e-15);
}

TEST(StereologySphere, SlabsCuttingTheSphereGiveCapVolumes)
{
  const double r = 1.7;
  for (double t : {-1.6, -0.9, 0.0, 0.4, 1.69}) {
    // {z >= t}: a cap of height r - t
    EXPECT_NEAR(sphere_slab_volume(r, t, 10.0), cap_volume(r, r - t), 1e-13) << t;
    // {z <= t}: the complement
    EXPECT_NEAR(sphere_slab_volume(r, -10.0, t), cap_volume(r, r + t), 1e-13) << t;
  }
  // a slab inside: sphere minus two caps
  EXPECT_NEAR(sphere_slab_volume(r, -0.5, 0.9),
              4.0 / 3.0 * kPi * r * r * r - cap_volume(r, r - 0.9) - cap_volume(r, r - 0.5), 1e-13);
  EXPECT_EQ(sphere_slab_volume(r, 1.8, 3.0), 0.0);
  EXPECT_EQ(sphere_slab_volume(r, 0.5, 0.5), 0.0);
}

TEST(StereologySphere, DiskBandAreaMatchesQuadratureOfChords)
{
  for (double rho : {0.3, 1.0, 2.5}) {
    for (double lo : {-3.0, -0.9, -0.2, 0.1}) {
      for (double hi : {-0.1, 0.25, 0.95, 3.0}) {
        auto chord = [&](double t) { return 2.0 * std::sqrt(std::max(0.0, rho * rho - t * t)); };
        const double exact =
            tanh_sinh(chord, std::max(lo, -rho), std::min(hi, rho));
        EXPECT_NEAR(disk_band_area(rho, lo, hi), exact, 1e-13 * rho * rho)
            << rho << " " << lo << " " << hi;
      }
    }
  }
  EXPECT_NEAR(disk_band_area(1.5, -5.0, 5.0), kPi * 2.25, 1e-14);
}

TEST(StereologySphere, QuadrantVolumeSpecialValues)
{
  EXPECT_NEAR(unit_sphere_quadrant_volume(0.0, 0.0), kPi / 3.0, 1e-15);
  EXPECT_NEAR(unit_sphere_quadrant_volume(-1.0, -1.0), 4.0 * kPi / 3.0, 1e-15);
  EXPECT_NEAR(unit_sphere_quadrant_volume(0.0, -1.0), 2.0 * kPi / 3.0, 1e-15);
  for (double p : {-0.7, 0.0, 0.35, 0.9}) {
    const double half_cap = 0.5 * cap_volume(1.0, 1.0 - p);
    EXPECT_NEAR(unit_sphere_quadrant_volume(p, 0.0), half_cap, 1e-14) << p;
    for (double q : {-0.95, -0.2, 0.3, 0.6})
      EXPECT_NEAR(unit_sphere_quadrant_volume(p, q), unit_sphere_quadrant_volume(q, p), 1e-14);
  }
  EXPECT_EQ(unit_sphere_quadrant_volume(0.8, 0.7), 0.0);  // p^2 + q^2 > 1
}

TEST(StereologySphere, BoxBandVolumeMatchesQuadratureOfVerticalCuts)
{
  const double r = 1.3;
  const double edges[] = {-2.0, -1.1, -0.6, 0.0, 0.45, 1.0, 1.29, 2.0};
  int checked = 0;
  for (double xlo : edges)
    for (double xhi : edges)
      for (double zlo : edges)
        for (double zhi : edges) {
          if (!(xlo < xhi) || !(zlo < zhi)) continue;
          auto cut = [&](double x) {
            const double rho2 = r * r - x * x;
            return rho2 > 0.0 ? disk_band_area(std::sqrt(rho2), zlo, zhi) : 0.0;
          };
          std::vector<double> breaks = {0.0};
          for (double t : {zlo, zhi})
            if (std::fabs(t) < r) {
              breaks.push_back(std::sqrt(r * r - t * t));
              breaks.push_back(-std::sqrt(r * r - t * t));
            }
          const double expected =
              piecewise_tanh_sinh(cut, std::max(xlo, -r), std::min(xhi, r), breaks);
          EXPECT_NEAR(sphere_box_band_volume(r, xlo, xhi, zlo, zhi), expected, 1e-12)
              << xlo << " " << xhi << " " << zlo << " " << zhi;
          ++checked;
        }
  EXPECT_GT(checked, 700);
}

TEST(StereologySphere, BoxBandVolumeMatchesMonteCarlo)
{
  // independent oracle (points in a cube), statistical tolerance of 5 sigma
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 400000;
  const double xlo = -0.3, xhi = 0.8, zlo = -0.9, zhi = 0.2;
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z < 1.0 && x >= xlo && x <= xhi && z >= zlo && z <= zhi) ++hits;
  }
  const double p = static_cast<double>(hits) / n;
  const double sigma = 8.0 * std::sqrt(p * (1.0 - p) / n);
  EXPECT_NEAR(sphere_box_band_volume(1.0, xlo, xhi, zlo, zhi), 8.0 * p, 5.0 * sigma);
}

// ---- lattices ------------------------------------------------------------------------------------

TEST(StereologyLattice, FccSlabOfWholePeriods)
{
  const double a = 1.7;
  const Packing p = fcc(a, 3, 7);
  const Box box = make_box(3 * a, 3 * a, 0.0, 7 * a, true);
  for (double z0 : {1.0 * a, 1.37 * a, 2.5 * a}) {
    for (int periods : {1, 2, 3}) {
      const double v = horizontal_slab_volume(p.view(), z0, z0 + periods * a);
      EXPECT_NEAR(v / (box.horizontal_area() * periods * a), kFccFraction, 1e-12);
    }
  }
  // uniform-radius path gives the same
  EXPECT_NEAR(horizontal_slab_volume(p.view(a / (2 * std::sqrt(2.0))), a, 3 * a) /
                  (box.horizontal_area() * 2 * a),
              kFccFraction, 1e-12);
}

TEST(StereologyLattice, FccCutThroughLayersAndBetween)
{
  // (001) layers every a/2 with 2 spheres per a^2: Phi = 2 pi R^2 / a^2 = pi / 4 in a layer,
  // and (2 pi / a^2) (a u - 2 u^2) at height u (0.146 a < u < a/4) above a layer.
  const double a = 2.0;
  const Packing p = fcc(a, 2, 6);
  const double area = 4.0 * a * a;
  EXPECT_NEAR(horizontal_cut_area(p.view(), 2.0 * a) / area, kPi / 4.0, 1e-13);
  for (double u : {0.2 * a, 0.25 * a, 0.3 * a}) {
    const double expected = 2.0 * kPi / (a * a) * (a * u - 2.0 * u * u);
    EXPECT_NEAR(horizontal_cut_area(p.view(), 2.0 * a + u) / area, expected, 1e-13) << u;
  }
}

TEST(StereologyLattice, SimpleCubicSlabOfWholePeriods)
{
  const double a = 1.0;
  const Packing p = simple_cubic(a, 4, 6);
  const Box box = make_box(4 * a, 4 * a, 0.0, 6 * a, true);
  const double v = horizontal_slab_volume(p.view(), 1.25 * a, 4.25 * a);
  EXPECT_NEAR(v / (box.horizontal_area() * 3 * a), kSimpleCubicFraction, 1e-12);
}

TEST(StereologyLattice, FccVerticalZonesWithPeriodicImages)
{
  // lateral zones one period wide at both x faces, central zone two periods; window of whole
  // periods inside the lattice: every zone has exactly the FCC fraction, and the spheres that
  // cross x = 0 count through their images.
  const double a = 1.0;
  const Packing p = fcc(a, 4, 6);
  const Box box = make_box(4 * a, 4 * a, 0.0, 6 * a, true);
  SummarySettings set;
  set.floor = 0.0;
  set.window_lo = 1.5 * a;
  set.window_hi = 3.5 * a;
  set.lateral_width = a;
  for (int axis : {0, 1}) {
    set.transverse_axis = axis;
    const Summary s = summarize(p.view(), box, set);
    EXPECT_NEAR(s.phi_lateral, kFccFraction, 1e-12) << axis;
    EXPECT_NEAR(s.phi_central, kFccFraction, 1e-12) << axis;
  }
  // a vertical slab of one period anywhere along x
  for (double c0 : {-0.3, 0.0, 0.61, 3.2}) {
    const double v = vertical_slab_volume(p.view(), box, 0, c0, c0 + a, 1.5 * a, 3.5 * a);
    EXPECT_NEAR(v / (a * 4 * a * 2 * a), kFccFraction, 1e-12) << c0;
  }
}

TEST(StereologyLattice, EmptyCentralZoneIsNaNNotZero)
{
  // Lateral zones that reach the middle of the box leave no central zone: its mean is NaN (no
  // measurement), not 0; the lateral mean is then the mean over the whole width. A central zone
  // of any width is measured as before.
  const double a = 1.0;
  const double r = a / (2.0 * std::sqrt(2.0));
  const Packing p = fcc(a, 4, 6);
  for (bool periodic : {true, false}) {
    const Box box = make_box(4 * a, 4 * a, 0.0, 6 * a, periodic);
    SummarySettings set;
    set.floor = 0.0;
    set.window_lo = 1.5 * a;
    set.window_hi = 3.5 * a;
    for (int axis : {0, 1}) {
      set.transverse_axis = axis;
      // lateral = half the box, more than half, and the default 7 R = 2.47 a of a box 4 a wide
      for (std::optional<double> lateral : {std::optional<double>(2.0 * a),
                                            std::optional<double>(3.0 * a),
                                            std::optional<double>()}) {
        set.lateral_width = lateral;
        const Summary s = summarize(p.view(), box, set);
        EXPECT_TRUE(std::isnan(s.phi_central)) << periodic << axis << s.phi_central;
        EXPECT_TRUE(std::isfinite(s.phi_lateral)) << periodic << axis;
        EXPECT_TRUE(std::isfinite(s.phi_bulk) && std::isfinite(s.phi_corrected));
        // the whole width: the volume fraction of the box slab in the window
        const double whole = vertical_slab_volume(p.view(), box, axis, 0.0, 4 * a, 1.5 * a,
                                                  3.5 * a) / (4 * a * 4 * a * 2 * a);
        EXPECT_NEAR(s.phi_lateral, whole, 1e-12) << periodic << axis;
      }
      // a central zone just wider than nothing, and the default in a box wide enough for it
      set.lateral_width = 1.9 * a;
      const Summary narrow = summarize(p.view(), box, set);
      EXPECT_TRUE(std::isfinite(narrow.phi_central)) << periodic << axis;
      EXPECT_GT(narrow.phi_central, 0.0) << periodic << axis;
      if (periodic) {
        set.lateral_width = a;
        EXPECT_NEAR(summarize(p.view(), box, set).phi_central, kFccFraction, 1e-12) << axis;
      }
    }
  }
  // the default lateral 7 R with a box wider than 14 R: a central zone again
  const Packing wide = fcc(a, 6, 6);
  const Box box = make_box(6 * a, 6 * a, 0.0, 6 * a, true);
  ASSERT_GT(6 * a, 14.0 * r);
  SummarySettings set;
  set.window_lo = 1.5 * a;
  set.window_hi = 3.5 * a;
  EXPECT_TRUE(std::isfinite(summarize(wide.view(), box, set).phi_central));
}

TEST(StereologyLattice, EmptyWindowIsNaNNotZero)
{
  // One layer of spheres on the floor: the default window [floor + 2R, window top] is empty, so
  // the zone means have no packing fraction (they read 0, as a measurement); a window given
  // across the layer measures it.
  Packing layer;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) layer.add(0.5 + i, 0.5 + j, 0.5, 0.5);
  const Box box = make_box(6.0, 6.0, 0.0, 4.0, true);
  SummarySettings set;
  set.floor = 0.0;
  set.lateral_width = 1.0;
  const Summary s = summarize(layer.view(), box, set);
  EXPECT_TRUE(std::isnan(s.phi_lateral)) << s.phi_lateral;
  EXPECT_TRUE(std::isnan(s.phi_central)) << s.phi_central;
  EXPECT_TRUE(std::isfinite(s.phi_bulk) && s.phi_bulk > 0.0);
  set.window_lo = 0.25;
  set.window_hi = 0.75;
  const Summary given = summarize(layer.view(), box, set);
  EXPECT_GT(given.phi_lateral, 0.0);
  EXPECT_GT(given.phi_central, 0.0);
}

TEST(StereologyLattice, FccSummaryOnWholePeriods)
{
  const double a = 1.0;
  const double r = a / (2.0 * std::sqrt(2.0));
  const int layers = 8;  // cells; top layer of centres at z = (layers - 1/2) a
  const Packing p = fcc(a, 4, layers);
  const Box box = make_box(4 * a, 4 * a, 0.0, 20 * a, true);
  SummarySettings set;
  set.floor = a;
  set.bulk_height = 2.0 * a;
  set.wall_factor = 1.0;
  set.column_width = a;  // every column holds two top-layer spheres: h_s = top layer + R
  const double surface = (layers - 0.5) * a + r;
  set.top_fraction = 4.0 * a / (surface - set.floor);  // z_top = floor + 4a
  const Summary s = summarize(p.view(), box, set);
  EXPECT_NEAR(s.surface, surface, 1e-12);
  EXPECT_NEAR(s.top, 5.0 * a, 1e-12);
  EXPECT_NEAR(s.phi_bulk, kFccFraction, 1e-12);
  EXPECT_NEAR(s.phi_corrected, kFccFraction, 1e-12);
  // <Z>: layers of centres at k a / 2 (k = 0 .. 2 layers - 1), equal populations
  EXPECT_NEAR(s.mean_height, 0.5 * a * (2 * layers - 1) / 2.0 - set.floor, 1e-12);
  EXPECT_EQ(s.sphere_count, 4.0 * 16 * layers);

  // with the 16/11 wall band [floor, floor + R]: the band volume scaled, the rest unchanged
  set.wall_factor = 16.0 / 11.0;
  const Summary c = summarize(p.view(), box, set);
  const double band = horizontal_slab_volume(p.view(), a, a + r);
  const double total = horizontal_slab_volume(p.view(), a, 5 * a);
  EXPECT_NEAR(c.phi_corrected, (total + (16.0 / 11.0 - 1.0) * band) / (16.0 * 4 * a), 1e-12);
  EXPECT_GT(c.phi_corrected, kFccFraction);
}

// ---- oracles on random polydisperse packings -----------------------------------------------

TEST(StereologyOracle, SlabVolumeEqualsExactQuadratureOfTheCutArea)
{
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Packing p = random_spheres(seed, 60, 8.0, 10.0);
    const Spheres s = p.view();
    const double z0 = 1.0 + 0.37 * seed, z1 = z0 + 4.3;
    // Phi(z) is a quadratic between consecutive sphere poles: 3-point Gauss-Legendre on each
    // piece integrates it exactly.
    std::vector<double> breaks = {z0, z1};
    for (size_t i = 0; i < p.radius.size(); ++i)
      for (double e : {p.xyz[3 * i + 2] - p.radius[i], p.xyz[3 * i + 2] + p.radius[i]})
        if (e > z0 && e < z1) breaks.push_back(e);
    std::sort(breaks.begin(), breaks.end());
    const double g = std::sqrt(0.6);
    double quad = 0.0;
    for (size_t k = 0; k + 1 < breaks.size(); ++k) {
      const double m = 0.5 * (breaks[k] + breaks[k + 1]), h = 0.5 * (breaks[k + 1] - breaks[k]);
      quad += h * (5.0 * horizontal_cut_area(s, m - g * h) + 8.0 * horizontal_cut_area(s, m) +
                   5.0 * horizontal_cut_area(s, m + g * h)) / 9.0;
    }
    const double exact = horizontal_slab_volume(s, z0, z1);
    EXPECT_NEAR(quad, exact, 1e-12 * exact) << seed;
    // and a plain midpoint rule converges to it (h^2)
    const int n = 20000;
    double mid = 0.0;
    for (int k = 0; k < n; ++k) mid += horizontal_cut_area(s, z0 + (k + 0.5) * (z1 - z0) / n);
    mid *= (z1 - z0) / n;
    EXPECT_NEAR(mid, exact, 1e-6 * exact) << seed;
  }
}

TEST(StereologyOracle, SlabFractionMatchesMonteCarloPoints)
{
  // non-overlapping polydisperse spheres (random sequential addition, periodic in x and y):
  // the fraction of random points inside a sphere is the slab's volume fraction
  const double L = 6.0, z0 = 1.5, z1 = 4.0;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(0.0, L), uz(0.0, 6.0), ur(0.4, 0.9);
  auto periodic_d2 = [&](const double *a, const double *b) {
    double d2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      double d = a[c] - b[c];
      if (c < 2) d -= L * std::round(d / L);
      d2 += d * d;
    }
    return d2;
  };
  Packing p;
  for (int attempt = 0; attempt < 4000 && p.radius.size() < 40; ++attempt) {
    const double c[3] = {ux(rng), ux(rng), uz(rng)}, r = ur(rng);
    bool free = true;
    for (size_t j = 0; j < p.radius.size() && free; ++j)
      free = periodic_d2(c, &p.xyz[3 * j]) >= std::pow(r + p.radius[j], 2);
    if (free) p.add(c[0], c[1], c[2], r);
  }
  ASSERT_GE(p.radius.size(), 20u);
  std::uniform_real_distribution<double> pz(z0, z1);
  const int n = 200000;
  int inside = 0;
  for (int k = 0; k < n; ++k) {
    const double q[3] = {ux(rng), ux(rng), pz(rng)};
    for (size_t i = 0; i < p.radius.size(); ++i)
      if (periodic_d2(q, &p.xyz[3 * i]) < p.radius[i] * p.radius[i]) {
        ++inside;
        break;
      }
  }
  const double frac = static_cast<double>(inside) / n;
  const double exact = horizontal_slab_volume(p.view(), z0, z1) / (L * L * (z1 - z0));
  EXPECT_GT(exact, 0.05);
  EXPECT_NEAR(exact, frac, 5.0 * std::sqrt(frac * (1 - frac) / n));
}

TEST(StereologyOracle, VerticalCutAreaIntegratesToTheSlabVolume)
{
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const Packing p = random_spheres(seed + 20, 25, 6.0, 8.0);
    for (bool periodic : {true, false}) {
      const Box box = make_box(6.0, 6.0, 0.0, 10.0, periodic);
      const double za = 2.0, zb = 5.5, c0 = -0.4, c1 = 2.3;
      std::vector<double> breaks;
      for (size_t i = 0; i < p.radius.size(); ++i) {
        const double r = p.radius[i], zc = p.xyz[3 * i + 2];
        for (int k = -1; k <= 1; ++k) {
          const double x = p.xyz[3 * i] + (periodic ? k * 6.0 : 0.0);
          breaks.insert(breaks.end(), {x - r, x + r});
          for (double t : {za - zc, zb - zc})
            if (std::fabs(t) < r) {
              const double w = std::sqrt(r * r - t * t);
              breaks.insert(breaks.end(), {x - w, x + w});
            }
        }
      }
      auto cut = [&](double c) { return vertical_cut_area(p.view(), box, 0, c, za, zb); };
      const double quad = piecewise_tanh_sinh(cut, c0, c1, breaks);
      const double exact = vertical_slab_volume(p.view(), box, 0, c0, c1, za, zb);
      EXPECT_NEAR(quad, exact, 1e-11 * exact) << seed << " " << periodic;
    }
  }
}

TEST(StereologyOracle, PeriodicImagesAndWalls)
{
  // one sphere across the x = 0 face
  Packing p;
  p.add(0.2, 1.0, 3.0, 0.5);
  const Box periodic = make_box(4.0, 2.0, 0.0, 6.0, true);
  const Box walls = make_box(4.0, 2.0, 0.0, 6.0, false);
  const double band = sphere_slab_volume(0.5, 2.8 - 3.0, 10.0);  // z window [2.8, inf)
  // the whole box along x holds the whole sphere band with images, the in-box part with walls
  EXPECT_NEAR(vertical_slab_volume(p.view(), periodic, 0, 0.0, 4.0, 2.8, 9.0), band, 1e-14);
  EXPECT_NEAR(vertical_slab_volume(p.view(), walls, 0, 0.0, 4.0, 2.8, 9.0),
              sphere_box_band_volume(0.5, -0.2, 3.8, -0.2, 6.0), 1e-14);
  EXPECT_LT(vertical_slab_volume(p.view(), walls, 0, 0.0, 4.0, 2.8, 9.0), band);
  // a cut at x = 3.9 meets the image at x = 4.2 (distance 0.3) only with periodic x
  const double rho = std::sqrt(0.25 - 0.09);
  EXPECT_NEAR(vertical_cut_area(p.view(), periodic, 0, 3.9, 0.0, 6.0), kPi * rho * rho, 1e-14);
  EXPECT_EQ(vertical_cut_area(p.view(), walls, 0, 3.9, 0.0, 6.0), 0.0);
  // horizontal cuts count the disk whole in both cases
  EXPECT_NEAR(horizontal_cut_area(p.view(), 3.0), kPi * 0.25, 1e-15);
}

// ---- profiles ---------------------------------------------------------------------------------

TEST(StereologyProfile, BinsTileTheRangeAndPlanesAreCuts)
{
  const Packing p = random_spheres(5, 50, 6.0, 8.0);
  const Box box = make_box(6.0, 6.0, 0.0, 10.0, true);
  const PlaneGrid grid{0.5, 8.5, 37};
  const std::vector<double> rows = profile(p.view(), box, 2, grid, 0.0, 0.0);
  double mean = 0.0;
  for (int k = 0; k < grid.n; ++k) {
    const double c = grid.position(k);
    EXPECT_NEAR(rows[3 * k], 0.5 + (k + 0.5) * 8.0 / 37, 1e-14);
    EXPECT_NEAR(rows[3 * k + 1], horizontal_cut_area(p.view(), c) / 36.0, 1e-14);
    const double lo = grid.lo + k * grid.bin_width();
    EXPECT_NEAR(rows[3 * k + 2],
                horizontal_slab_volume(p.view(), lo, lo + grid.bin_width()) /
                    (36.0 * grid.bin_width()),
                1e-13);
    mean += rows[3 * k + 2] / grid.n;
  }
  EXPECT_NEAR(mean, horizontal_slab_volume(p.view(), 0.5, 8.5) / (36.0 * 8.0), 1e-13);
}

TEST(StereologyProfile, BinsFarNarrowerThanASphereStillSeeIt)
{
  // A bin of 1e-13 around z = 0.5: the sphere below reaches 1e13 bins beyond it, past int. The
  // cast of that bin index gave INT_MIN and the sphere was skipped: Phi 0 in its middle.
  const Packing p = random_spheres(5, 50, 6.0, 8.0);
  const Box box = make_box(6.0, 6.0, 0.0, 10.0, true);
  for (double width : {1e-6, 1e-13}) {
    const PlaneGrid grid{3.0, 3.0 + width, 1};
    const std::vector<double> rows = profile(p.view(), box, 2, grid, 0.0, 0.0);
    const double at_plane = horizontal_cut_area(p.view(), grid.position(0)) / 36.0;
    ASSERT_GT(at_plane, 0.1);
    EXPECT_NEAR(rows[1], at_plane, 1e-14) << width;
    EXPECT_NEAR(rows[2], at_plane, 1e-5) << width;  // the bin mean tends to the plane's value
  }
}

TEST(StereologyProfile, VerticalProfileMatchesDirectSums)
{
  const Packing p = random_spheres(9, 50, 6.0, 8.0);
  for (bool periodic : {true, false}) {
    const Box box = make_box(6.0, 5.0, 0.0, 10.0, periodic);
    for (int axis : {0, 1}) {
      const PlaneGrid grid{box.lo[axis], box.hi[axis], 23};
      const double za = 1.5, zb = 6.0;
      const std::vector<double> rows = profile(p.view(), box, axis, grid, za, zb);
      const double plane_area = box.length(1 - axis) * (zb - za);
      double mean = 0.0;
      for (int k = 0; k < grid.n; ++k) {
        const double c = grid.position(k), lo = grid.lo + k * grid.bin_width();
        EXPECT_NEAR(rows[3 * k + 1], vertical_cut_area(p.view(), box, axis, c, za, zb) / plane_area,
                    1e-14);
        EXPECT_NEAR(rows[3 * k + 2],
                    vertical_slab_volume(p.view(), box, axis, lo, lo + grid.bin_width(), za, zb) /
                        (plane_area * grid.bin_width()),
                    1e-13);
        mean += rows[3 * k + 2] / grid.n;
      }
      // the bins together hold the window volume (all of it with images)
      double full = vertical_slab_volume(p.view(), box, axis, grid.lo, grid.hi, za, zb);
      EXPECT_NEAR(mean, full / (plane_area * box.length(axis)), 1e-13);
      if (periodic) EXPECT_NEAR(full, horizontal_slab_volume(p.view(), za, zb), 1e-12);
    }
  }
}

// An empty window (zb <= za) cuts no area: every row's Phi and bin mean are NaN (they were 0,
// which reads as an empty layer); the plane positions stay.
TEST(StereologyProfile, EmptyWindowGivesNaNRows)
{
  const Packing p = random_spheres(9, 50, 6.0, 8.0);
  const Box box = make_box(6.0, 5.0, 0.0, 10.0, true);
  for (double zb : {2.0, 1.0}) {
    const PlaneGrid grid{0.0, 6.0, 4};
    const std::vector<double> rows = profile(p.view(), box, 0, grid, 2.0, zb);
    for (int k = 0; k < grid.n; ++k) {
      EXPECT_DOUBLE_EQ(rows[3 * k], grid.position(k));
      EXPECT_TRUE(std::isnan(rows[3 * k + 1])) << k;
      EXPECT_TRUE(std::isnan(rows[3 * k + 2])) << k;
    }
  }
}

TEST(StereologyProfile, FccProfileBinMeansAreExact)
{
  // bins of one period along z and along x hold the FCC fraction exactly
  const double a = 1.0;
  const Packing p = fcc(a, 4, 6);
  const Box box = make_box(4 * a, 4 * a, 0.0, 6 * a, true);
  const std::vector<double> z = profile(p.view(), box, 2, PlaneGrid{1.0, 5.0, 4}, 0, 0);
  const std::vector<double> x = profile(p.view(), box, 0, PlaneGrid{0.0, 4.0, 4}, 1.5, 4.5);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(z[3 * k + 2], kFccFraction, 1e-12);
    EXPECT_NEAR(x[3 * k + 2], kFccFraction, 1e-12);
  }
}

// ---- surface height, layouts, validation ----------------------------------------------------

TEST(StereologySurface, FlatTopAndOneStraySphere)
{
  const double a = 1.0, r = a / (2.0 * std::sqrt(2.0));
  Packing p = fcc(a, 4, 5);
  const Box box = make_box(4 * a, 4 * a, 0.0, 10 * a, true);
  const ColumnGrid grid = make_column_grid(box, a);
  ASSERT_EQ(grid.size(), 16);
  // a box a whole number of columns wide in other units (6 columns of 0.2: 1.2 / 0.2 is
  // 5.999... in doubles) has that number of columns, whatever the units
  for (double unit : {1.0, 0.2, 0.1, 3e-3, 1e-6, 7.0})
    EXPECT_EQ(make_column_grid(make_box(6 * unit, 6 * unit, 0.0, 1.0, true), unit).n[0], 6)
        << "unit " << unit;
  std::vector<double> tops(grid.size(), -std::numeric_limits<double>::infinity());
  accumulate_column_tops(p.view(), grid, tops.data());
  const double flat = 4.5 * a + r;
  EXPECT_NEAR(surface_height(tops.data(), grid.size(), 0.0), flat, 1e-14);
  // a stray sphere 3a above the surface shifts h_s by 3a / 16 only
  p.add(1.5 * a, 2.5 * a, 7.5 * a, r);
  std::fill(tops.begin(), tops.end(), -std::numeric_limits<double>::infinity());
  accumulate_column_tops(p.view(), grid, tops.data());
  EXPECT_NEAR(surface_height(tops.data(), grid.size(), 0.0), flat + 3.0 * a / 16.0, 1e-14);
  // empty columns are skipped; all empty gives the fallback
  std::vector<double> empty(4, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(surface_height(empty.data(), 4, -2.5), -2.5);
  empty[2] = 3.0;
  EXPECT_EQ(surface_height(empty.data(), 4, -2.5), 3.0);
}

TEST(StereologyLayout, IndexListAndUniformRadiusAgreeWithPlainArrays)
{
  Packing p = random_spheres(4, 30, 5.0, 5.0);
  std::fill(p.radius.begin(), p.radius.end(), 0.6);
  const Box box = make_box(5.0, 5.0, 0.0, 8.0, true);
  SummarySettings set;
  const Summary plain = summarize(p.view(), box, set);
  const Summary uniform = summarize(p.view(0.6), box, set);
  EXPECT_DOUBLE_EQ(plain.phi_bulk, uniform.phi_bulk);
  EXPECT_DOUBLE_EQ(plain.phi_corrected, uniform.phi_corrected);
  EXPECT_DOUBLE_EQ(plain.phi_lateral, uniform.phi_lateral);
  // an index list selecting the even spheres equals a packing of the even spheres
  std::vector<int> even;
  Packing half;
  for (int i = 0; i < 30; i += 2) {
    even.push_back(i);
    half.add(p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2], p.radius[i]);
  }
  Spheres sel = p.view();
  sel.index = even.data();
  sel.count = static_cast<int>(even.size());
  set.lateral_width = 1.5;  // a central zone (the default 7 R = 4.2 leaves none in a box 5 wide)
  const Summary a = summarize(sel, box, set), b = summarize(half.view(), box, set);
  EXPECT_DOUBLE_EQ(a.phi_bulk, b.phi_bulk);
  EXPECT_DOUBLE_EQ(a.mean_height, b.mean_height);
  EXPECT_DOUBLE_EQ(a.phi_central, b.phi_central);
  EXPECT_NE(a.phi_bulk, plain.phi_bulk);
}

TEST(StereologyValidation, BadSettingsThrowNamingTheArgument)
{
  auto message = [](const SummarySettings &s) {
    try {
      validate(s);
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SummarySettings s;
  EXPECT_EQ(message(s), "");
  s.top_fraction = 0.0;
  EXPECT_NE(message(s).find("top_fraction"), std::string::npos);
  s.top_fraction = 1.2;
  EXPECT_NE(message(s).find("top_fraction = 1.2 is outside the allowed range (0, 1]"),
            std::string::npos);
  s.top_fraction = -0.2;  // quoted as typed, without a round-off tail
  EXPECT_NE(message(s).find("top_fraction = -0.2 is outside the allowed range (0, 1]"),
            std::string::npos);
  s = SummarySettings{};
  s.window_lo = 3.0;
  s.window_hi = 2.0;
  EXPECT_NE(message(s).find("window"), std::string::npos);
  s = SummarySettings{};
  s.bulk_height = -1.0;
  EXPECT_NE(message(s).find("bulk"), std::string::npos);
  s = SummarySettings{};
  s.lateral_width = 0.0;
  EXPECT_NE(message(s).find("lateral"), std::string::npos);
  Packing p;
  p.add(0, 0, 0, 1);
  const Box box = make_box(1, 1, 0, 1, true);
  EXPECT_THROW(profile(p.view(), box, 2, PlaneGrid{1.0, 1.0, 3}, 0, 0), std::invalid_argument);
  EXPECT_THROW(profile(p.view(), box, 2, PlaneGrid{0.0, 1.0, 0}, 0, 0), std::invalid_argument);
  EXPECT_THROW(make_column_grid(box, 0.0), std::invalid_argument);
  // a width far below the box's (1e-4 of a unit box: 10000 columns a side) is refused, never
  // cast to a grid that cannot be allocated
  EXPECT_THROW(make_column_grid(box, 1e-4), std::invalid_argument);
  EXPECT_THROW(make_column_grid(box, 1e-300), std::invalid_argument);
  EXPECT_EQ(make_column_grid(box, 1.0 / 4096).n[0], 4096);
  // the default width (not the user's) is widened instead: a box 5000 diameters wide along x
  // (create_packing's summary ended the run there) has 4096 columns along x, 3 along y
  Packing wide;
  wide.add(2.5, 1.0, 0.5, 0.5);
  const Box long_box = make_box(5000.0, 3.0, 0.0, 10.0, true);
  EXPECT_THROW(make_column_grid(long_box, 1.0), std::invalid_argument);
  const ColumnGrid widened = surface_column_grid(long_box, SummarySettings{}, 0.5);
  EXPECT_EQ(widened.n[0], 4096);
  EXPECT_EQ(widened.n[1], 3);
  SummarySettings given;
  given.column_width = 1.0;
  EXPECT_THROW(surface_column_grid(long_box, given, 0.5), std::invalid_argument);
  EXPECT_NEAR(summarize(wide.view(), long_box, SummarySettings{}).surface, 1.0, 1e-12);
  EXPECT_NO_THROW(validate(PlaneGrid{0.0, 1.0, 3}));
  try {
    validate(PlaneGrid{6.5, 5.0, 10});
    ADD_FAILURE() << "no exception for planes lo > hi";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find(
                  "planes lo = 6.5 is outside the allowed range (-inf, hi) = (-inf, 5)"),
              std::string::npos)
        << e.what();
  }
}
