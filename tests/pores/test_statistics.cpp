// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Pore statistics: histograms and nu on exact lattices, sub-box selection, Gotoh's P0 (eq. 8-9)
// against the sampled one, monodisperse check.
#include <gtest/gtest.h>

#include <cmath>

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
  // rho_v(v): same weights at v = xi^3.
  const double vw = s.v.width();
  EXPECT_NEAR(s.v.density(static_cast<std::size_t>(xo * xo * xo / vw)) * vw, 1.0 / 3, 1e-12);
}

TEST(PoreStatistics, RegionDefaultsAndExplicitBounds) {
  Box box;
  box.lo = {0, 0, 0};
  box.hi = {32, 32, 40};
  box.periodic = {true, false, false};
  RegionSpec spec;  // defaults: periodic x whole, 2R from the y and z faces
  Region r = make_region(box, 0.5, spec);
  EXPECT_EQ(r.lo, (std::array<double, 3>{0, 1, 1}));
  EXPECT_EQ(r.hi, (std::array<double, 3>{32, 31, 39}));
  spec.units = {RegionSpec::Units::kRadiiFromLo, RegionSpec::Units::kRadiiFromLo, RegionSpec::Units::kRadiiFromLo};
  spec.lo[2] = 2;
  spec.hi[2] = 20;  // the paper's 18 R window starting 2 R above the floor
  r = make_region(box, 0.5, spec);
  EXPECT_DOUBLE_EQ(r.lo[2], 1.0);
  EXPECT_DOUBLE_EQ(r.hi[2], 10.0);
  EXPECT_TRUE(r.contains({0.0, 5.0, 5.0}));
  EXPECT_FALSE(r.contains({5.0, 0.5, 5.0}));
  spec.lo[2] = 90;
  spec.hi[2] = 95;
  EXPECT_THROW(make_region(box, 0.5, spec), std::invalid_argument);
}

TEST(PoreStatistics, GotohPercusYevick) {
  for (double phi : {0.584, 0.606}) {
    EXPECT_DOUBLE_EQ(gotoh_p0(0.0, phi), 1.0);
    EXPECT_NEAR(gotoh_p0(1.0, phi), 1.0 - phi, 1e-15);  // eq. 8 and eq. 9 meet at sigma = 1
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
