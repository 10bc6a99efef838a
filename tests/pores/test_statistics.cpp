// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Pore statistics: histograms, nu, n_v(v) and rho_v(v) on exact lattices and on an analytic
// P(xi), the default selection (floor, free surface h_s, side walls from the data), Gotoh's P0
// (eq. 8, and the form replacing the printed eq. 9) against the sampled one, monodisperse check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "pores_test_util.h"
#include "tapmc_pores/analysis.h"
#include "tapmc_pores/tessellation.h"

namespace {

using namespace tapmc::pores;
using pores_test::Packing;

TEST(PoreStatistics, FccHistogramAndNu) {
  const Packing p = pores_test::fcc(3, 0.5);
  PoreOptions o;
  o.radius = p.radius;
  const Tessellation t(p.box, p.xyz, p.ids, o);
  PoreStatistics s(HistogramSpec{1.5, 150});
  for (const Pore& pore : t.pores()) s.add(pore);
  const double xt = std::sqrt(1.5) - 1, xo = std::sqrt(2.0) - 1;
  EXPECT_EQ(s.pores, 3 * p.size());
  EXPECT_EQ(s.degenerate, p.size());
  EXPECT_NEAR(s.nu(), (2 * xt * xt * xt + xo * xo * xo) / 3, 1e-12);  // nu = <xi^3>
  // P(xi) integrates to 1 and has two peaks of weight 2/3 and 1/3.
  double integral = 0;
  for (std::size_t i = 0; i < s.xi.bins(); ++i) integral += s.xi.density(i) * s.xi.width();
  EXPECT_NEAR(integral, 1.0, 1e-12);
  EXPECT_NEAR(s.xi.density(static_cast<std::size_t>(xt / 0.01)) * 0.01, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.xi.density(static_cast<std::size_t>(xo / 0.01)) * 0.01, 1.0 / 3, 1e-12);
  // n_v(v), the number density of v = xi^3: same weights at v = xi^3, integral 1.
  const double vw = s.v.width();
  const auto bin_t = static_cast<std::size_t>(xt * xt * xt / vw), bin_o = static_cast<std::size_t>(xo * xo * xo / vw);
  ASSERT_NE(bin_t, bin_o);
  EXPECT_NEAR(s.v.density(bin_o) * vw, 1.0 / 3, 1e-12);
  EXPECT_NEAR(s.v.density(bin_t) * vw, 2.0 / 3, 1e-12);
  // rho_v(v) = v n_v(v), the paper's volume distribution (section IV.B): each peak weighs its
  // share of nu, xi^3 times its fraction, and the whole integrates to nu, not to 1.
  EXPECT_NEAR(s.v.weighted_density(bin_o) * vw, xo * xo * xo / 3, 1e-12);
  EXPECT_NEAR(s.v.weighted_density(bin_t) * vw, 2 * xt * xt * xt / 3, 1e-12);
  double n_integral = 0, rho_integral = 0;
  for (std::size_t i = 0; i < s.v.bins(); ++i) {
    n_integral += s.v.density(i) * vw;
    rho_integral += s.v.weighted_density(i) * vw;
  }
  EXPECT_NEAR(n_integral, 1.0, 1e-12);
  EXPECT_NEAR(rho_integral, s.nu(), 1e-12);
}

// The conversion of section IV.B on an analytic case: P(xi) uniform on [a, b]. Then
// n_v(v) = P(xi) / (3 xi^2) and rho_v(v) = (xi/3) P(xi) with xi = v^(1/3), whose averages over a
// v bin [v0, v1) are, with x = clip(v^(1/3), a, b), (x1 - x0) / ((b - a) w) and
// (x1^4 - x0^4) / (4 (b - a) w): rho_v dv = xi^3 P(xi) dxi. The pores are M quantiles of P, so
// every bin holds its expected count to within one pore: a bound of 1/M on each bin's weight.
TEST(PoreStatistics, VolumeDistributionIsXiOverThreeTimesP) {
  const double a = 0.25, b = 0.65;
  const std::size_t m = 400000;
  PoreStatistics whole(HistogramSpec{1.0, 100}), first(HistogramSpec{1.0, 100}), second(HistogramSpec{1.0, 100});
  PoreStatistics clipped(HistogramSpec{0.6, 100});  // pores with xi >= 0.6 overflow
  for (std::size_t k = 0; k < m; ++k) {
    Pore pore;
    pore.xi = a + (b - a) * (static_cast<double>(k) + 0.5) / static_cast<double>(m);
    whole.add(pore);
    (k % 3 == 0 ? first : second).add(pore);
    clipped.add(pore);
  }
  first.merge(second);  // merging keeps the sums of v per bin
  const double nu = (std::pow(b, 4) - std::pow(a, 4)) / (4 * (b - a));
  EXPECT_NEAR(whole.nu(), nu, 1e-9);
  const Histogram& v = whole.v;
  const double w = v.width(), bound = 1.0 / static_cast<double>(m);
  auto clip = [&](double edge) { return std::min(b, std::max(a, std::cbrt(edge))); };
  double n_integral = 0, rho_integral = 0;
  for (std::size_t i = 0; i < v.bins(); ++i) {
    const double v0 = v.bin_lo(i), v1 = v0 + w, x0 = clip(v0), x1 = clip(v1);
    EXPECT_NEAR(v.density(i) * w, (x1 - x0) / (b - a), bound) << "bin " << i;
    EXPECT_NEAR(v.weighted_density(i) * w, (std::pow(x1, 4) - std::pow(x0, 4)) / (4 * (b - a)), v1 * bound)
        << "bin " << i;
    // Each v of the bin is within w/2 of its centre: |rho_v - v_centre n_v| <= (w/2) n_v.
    EXPECT_LE(std::abs(v.weighted_density(i) - v.bin_centre(i) * v.density(i)), 0.5 * w * v.density(i) + 1e-12);
    EXPECT_NEAR(first.v.weighted_density(i), v.weighted_density(i), 1e-12 * (1 + v.weighted_density(i)));
    n_integral += v.density(i) * w;
    rho_integral += v.weighted_density(i) * w;
  }
  EXPECT_NEAR(n_integral, 1.0, 1e-12);
  EXPECT_NEAR(rho_integral, whole.nu(), 1e-12);  // int rho_v(v) dv = nu (section IV.B)
  // Out-of-range pores count in the normalisation but carry no volume into the bins: the
  // integral is then the in-range part of nu, int_a^0.6 xi^3 P(xi) dxi.
  double clipped_integral = 0;
  for (std::size_t i = 0; i < clipped.v.bins(); ++i)
    clipped_integral += clipped.v.weighted_density(i) * clipped.v.width();
  EXPECT_GT(clipped.v.overflow(), 0u);
  EXPECT_NEAR(clipped_integral, (std::pow(0.6, 4) - std::pow(a, 4)) / (4 * (b - a)), 0.6 * 0.6 * 0.6 * bound);
}

// A packing resting on a floor at z = 2 in a box starting at z = -5 (a DEM dump): simple cubic
// layers of R = 0.5 at contact, 16 x 16 columns per layer; the top layer has one sphere missing
// and one stray sphere 3 diameters higher.
Packing layered_packing(int layers, bool periodic_xy) {
  Packing p;
  p.radius = 0.5;
  for (int k = 0; k < layers; ++k)
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j)
        if (!(k == layers - 1 && i == 3 && j == 4)) p.add(0.5 + i, 0.5 + j, 2.5 + k);
  p.add(7.5, 7.5, 2.5 + layers - 1 + 3.0);  // stray sphere above column (7, 7)
  p.box.lo = {periodic_xy ? 0.0 : -3.0, periodic_xy ? 0.0 : -3.0, -5.0};
  p.box.hi = {periodic_xy ? 16.0 : 20.0, periodic_xy ? 16.0 : 20.0, 40.0};
  p.box.periodic = {periodic_xy, periodic_xy, false};
  return p;
}

TEST(PoreSelection, SurfaceHeightIsTheMeanColumnTop) {
  const Packing p = layered_packing(10, true);
  // 256 columns one diameter wide (2R): every column's top is 2 + 10 = 12, except the column
  // without its top sphere (11) and the column of the stray sphere (15).
  const double expected = 12.0 + (-1.0 + 3.0) / 256.0;
  EXPECT_NEAR(surface_height(p.xyz, p.radius, {0, 0}, {16, 16}, 2 * p.radius), expected, 1e-12);
  // Columns of 4 spheres (width 2): 64 columns; the missing sphere is hidden by its neighbours.
  EXPECT_NEAR(surface_height(p.xyz, p.radius, {0, 0}, {16, 16}, 2.0), 12.0 + 3.0 / 64.0, 1e-12);
  // Width above the box: one column, the highest top.
  EXPECT_NEAR(surface_height(p.xyz, p.radius, {0, 0}, {16, 16}, 100.0), 15.0, 1e-12);
  // Empty columns are skipped: a wider tiling around the same spheres gives the same height.
  EXPECT_NEAR(surface_height(p.xyz, p.radius, {-16, -16}, {32, 32}, 1.0), expected, 1e-12);
}

// The column count is compute stereo/profile's: 1.2 / 0.2 = 5.999... in doubles still gives 6
// columns (one sphere each: h_s the mean of their 6 tops, not 5 columns with one top hidden),
// and a width far below the spheres' size widens to kMaxColumnsPerAxis columns a side.
TEST(PoreSelection, SurfaceColumnsAreTheComputesColumns) {
  std::vector<double> xyz;
  for (int i = 0; i < 6; ++i) {
    const double height[] = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
    xyz.insert(xyz.end(), {0.1 + 0.2 * i, 0.1, height[i]});
  }
  ASSERT_LT(1.2 / 0.2, 6.0);
  EXPECT_NEAR(surface_height(xyz, 0.1, {0, 0}, {1.2, 0.2}, 0.2), 3.5 + 0.1, 1e-12);
  const std::vector<double> one{0.5, 0.5, 1.0};
  EXPECT_NEAR(surface_height(one, 0.1, {0, 0}, {1e6, 1e6}, 1e-6), 1.1, 1e-12);
}

TEST(PoreSelection, DefaultRegionIsThePackingNotTheBox) {
  for (bool periodic_xy : {true, false}) {
    const Packing p = layered_packing(10, periodic_xy);
    const PackingBounds packing = find_packing(p.box, p.xyz, p.radius);
    EXPECT_TRUE(packing.free_surface);
    EXPECT_DOUBLE_EQ(packing.lo[2], 2.0);  // floor: the lowest sphere bottom, not the box's -5
    EXPECT_NEAR(packing.hi[2], 12.0 + 2.0 / 256.0, 1e-12);
    RegionSpec spec;  // 2R above the floor, 4R below h_s; 2R from the side walls or whole
    Region r = make_region(p.box, packing, p.radius, spec);
    EXPECT_DOUBLE_EQ(r.lo[2], 3.0);
    EXPECT_NEAR(r.hi[2], packing.hi[2] - 2.0, 1e-12);
    if (periodic_xy) {
      EXPECT_EQ(r.lo[0], 0.0);
      EXPECT_EQ(r.hi[1], 16.0);
    } else {  // side walls where the outermost spheres are (x, y in [0, 16]), not the box
      EXPECT_DOUBLE_EQ(r.lo[0], 1.0);
      EXPECT_DOUBLE_EQ(r.hi[1], 15.0);
    }
    // The paper's window (--paper-window = --radii --z 2:20) counts from the floor.
    spec.units.fill(RegionSpec::Units::kRadiiFromLo);
    spec.lo[2] = 2;
    spec.hi[2] = 20;
    r = make_region(p.box, packing, p.radius, spec);
    EXPECT_DOUBLE_EQ(r.lo[2], 3.0);
    EXPECT_DOUBLE_EQ(r.hi[2], 12.0);
    // An explicit floor replaces the lowest sphere bottom.
    const PackingBounds floored = find_packing(p.box, p.xyz, p.radius, 1.5);
    EXPECT_DOUBLE_EQ(floored.lo[2], 1.5);
    EXPECT_DOUBLE_EQ(floored.lowest_bottom, 2.0);
    EXPECT_DOUBLE_EQ(make_region(p.box, floored, p.radius, spec).lo[2], 2.5);
  }
}

TEST(PoreSelection, BadFloorsAndEmptyRegionsAreRefused) {
  Packing p = layered_packing(2, true);  // floor 2, h_s ~ 4: 4R tall, less than 2R + 4R
  const PackingBounds packing = find_packing(p.box, p.xyz, p.radius);
  try {
    make_region(p.box, packing, p.radius, RegionSpec{});
    FAIL() << "empty region accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("empty selection region along z"), std::string::npos) << what;
    EXPECT_NE(what.find("--surface-gap"), std::string::npos) << what;
  }
  EXPECT_THROW(find_packing(p.box, p.xyz, p.radius, 10.0), std::invalid_argument);  // above h_s
  p.box.periodic[2] = true;  // no floor along a periodic z
  EXPECT_THROW(find_packing(p.box, p.xyz, p.radius, 2.0), std::invalid_argument);
  const PackingBounds whole = find_packing(p.box, p.xyz, p.radius);
  EXPECT_FALSE(whole.free_surface);
  const Region r = make_region(p.box, whole, p.radius, RegionSpec{});
  EXPECT_EQ(r.lo, p.box.lo);
  EXPECT_EQ(r.hi, p.box.hi);
}

TEST(PoreSelection, ExplicitBoundsAreClippedToTheBox) {
  Box box;
  box.lo = {0, 0, 0};
  box.hi = {32, 32, 40};
  box.periodic = {true, false, false};
  PackingBounds packing;
  packing.lo = {0, 0, 0};
  packing.hi = {32, 32, 30};
  packing.free_surface = true;
  RegionSpec spec;
  spec.lo = {-10, 5, 1};
  spec.hi = {50, 6, 39};
  const Region r = make_region(box, packing, 0.5, spec);
  EXPECT_EQ(r.lo, (std::array<double, 3>{0, 5, 1}));
  EXPECT_EQ(r.hi, (std::array<double, 3>{32, 6, 39}));
  EXPECT_TRUE(r.contains({0.0, 5.0, 5.0}));
  EXPECT_FALSE(r.contains({5.0, 6.0, 5.0}));
  spec.lo[2] = 90;
  spec.hi[2] = 95;
  EXPECT_THROW(make_region(box, packing, 0.5, spec), std::invalid_argument);
}

// --cylinder: the disk RC - wall_gap R about the axis in x and y (the side-wall rule measured
// radially), z by its own rule; its volume, its random points, and the refused tubes.
TEST(PoreSelection, CylinderSelectsTheDiskInsideTheTube) {
  Box box;
  box.lo = {0, 0, 0};
  box.hi = {10, 10, 30};
  box.periodic = {false, false, false};
  PackingBounds packing;
  packing.lo = {0, 0, 0};
  packing.hi = {10, 10, 20};
  packing.free_surface = true;
  RegionSpec spec;
  spec.cylinder.given = true;
  spec.cylinder.centre_x = 5;
  spec.cylinder.centre_y = 5;
  spec.cylinder.radius = 5;
  spec.cylinder.text = "5:5:5";
  const Region r = make_region(box, packing, 0.5, spec);
  ASSERT_TRUE(r.disk);
  EXPECT_DOUBLE_EQ(r.disk_radius, 4.0);
  EXPECT_EQ(r.lo, (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(r.hi, (std::array<double, 3>{9, 9, 18}));
  EXPECT_TRUE(r.contains({5.0 + 3.99, 5.0, 5.0}));
  EXPECT_FALSE(r.contains({8.5, 8.5, 5.0}));  // a corner of the bounding square: outside the disk
  EXPECT_NEAR(r.volume(), 3.14159265358979 * 16.0 * 17.0, 1e-9);
  for (std::size_t i = 0, n = 2000; i < n; ++i) {
    const auto points = random_points(r, 1, 7, i);
    EXPECT_TRUE(r.contains({points[0], points[1], points[2]})) << points[0] << " " << points[1];
  }
  spec.cylinder.centre_x = 6;  // the tube leaves the box
  EXPECT_THROW(make_region(box, packing, 0.5, spec), std::invalid_argument);
  spec.cylinder.centre_x = 5;
  spec.cylinder.radius = 1;  // not more than the wall gap 2R
  EXPECT_THROW(make_region(box, packing, 0.5, spec), std::invalid_argument);
  spec.cylinder.radius = 5;
  box.periodic[1] = true;
  EXPECT_THROW(make_region(box, packing, 0.5, spec), std::invalid_argument);
}

TEST(PoreStatistics, GotohPercusYevick) {
  for (double phi : {0.584, 0.606}) {
    EXPECT_DOUBLE_EQ(gotoh_p0(0.0, phi), 1.0);
    EXPECT_NEAR(gotoh_p0(1.0, phi), 1.0 - phi, 1e-15);  // both branches meet at sigma = 1
    // -ln P0 is continuous with its slope at sigma = 1 (one-sided finite differences) ...
    auto minus_log = [&](double sigma) { return -std::log(gotoh_p0(sigma, phi)); };
    const double h = 1e-5, below1 = (minus_log(1.0) - minus_log(1 - h)) / h,
                 above1 = (minus_log(1 + h) - minus_log(1.0)) / h;
    EXPECT_NEAR(gotoh_p0(1.0 + 1e-12, phi), 1.0 - phi, 1e-10);
    EXPECT_NEAR(above1, below1, 1e-3 * below1);
    EXPECT_NEAR(above1, 3 * phi / (1 - phi), 1e-3 * above1);
    // ... and for sigma > 1 its third derivative is 6 phi beta P / rho with the PY pressure
    // beta P / rho = (1 + phi + phi^2) / (1 - phi)^3 (third difference of a cubic is exact).
    const double d = 0.1, third = (minus_log(1.5 + 3 * d) - 3 * minus_log(1.5 + 2 * d) + 3 * minus_log(1.5 + d) -
                                   minus_log(1.5)) / (d * d * d);
    EXPECT_NEAR(third, 6 * phi * (1 + phi + phi * phi) / std::pow(1 - phi, 3), 1e-6 * third);
    double previous = 1.0;
    for (double sigma = 0.05; sigma < 2.0; sigma += 0.05) {  // a survival function: decreasing
      const double value = gotoh_p0(sigma, phi);
      EXPECT_LT(value, previous);
      EXPECT_GT(value, 0.0);
      previous = value;
    }
  }
  EXPECT_THROW(gotoh_p0(0.5, 1.0), std::invalid_argument);
}

TEST(PoreStatistics, SampledP0MatchesExactVolumeFractionBelowContact) {
  // For sigma <= 1 the balls of radius sigma R around hard-sphere centres are disjoint, so in a
  // triply periodic box P0(sigma) = 1 - phi sigma^3 exactly (eq. 8); sampled within 5 sigma.
  const Packing p = pores_test::random_packing(300, 8.0, {true, true, true}, 3);
  PoreOptions o;
  o.radius = p.radius;
  const Tessellation t(p.box, p.xyz, p.ids, o);
  const double phi = p.size() * 4.0 / 3.0 * M_PI * std::pow(p.radius, 3) / p.box.volume();
  P0Statistics p0(2.0, 41);
  const Region whole{p.box.lo, p.box.hi};
  const std::size_t samples = 200000;
  for (double d : t.nearest_centre_distances(random_points(whole, samples, 11, 0))) p0.add_distance(d / p.radius);
  EXPECT_NEAR(p0.phi(), phi, 5 * std::sqrt(phi * (1 - phi) / samples));
  for (std::size_t k = 0; k < p0.steps() && p0.sigma(k) <= 1.0; ++k) {
    const double expected = 1 - phi * std::pow(p0.sigma(k), 3);
    EXPECT_NEAR(p0.p0(k), expected, 5 * std::sqrt(expected * (1 - expected) / samples) + 1e-12) << p0.sigma(k);
  }
  EXPECT_DOUBLE_EQ(p0.p0(0), 1.0);
}

TEST(PoreStatistics, PolydisperseInputIsRefused) {
  Frame f;
  f.ids = {1, 2, 3};
  f.xyz = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  f.radius = {0.5, 0.5, 0.5};
  EXPECT_DOUBLE_EQ(common_radius(f, 0.0).radius, 0.5);
  EXPECT_THROW(common_radius(f, 0.6), std::invalid_argument);  // --radius disagrees with the column
  f.radius[2] = 0.55;
  try {
    common_radius(f, 0.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("polydisperse"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("atom 3"), std::string::npos);
  }
  f.radius.clear();
  EXPECT_THROW(common_radius(f, 0.0), std::invalid_argument);  // no column, no --radius
  EXPECT_DOUBLE_EQ(common_radius(f, 0.7).radius, 0.7);
}

}  // namespace
