// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Exact lattices: FCC, HCP, simple cubic pores per sphere and their sizes, exact and perturbed.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "pores_test_util.h"
#include "tapmc_pores/tessellation.h"

namespace {

using pores_test::Packing;
using tapmc::pores::Pore;
using tapmc::pores::PoreOptions;
using tapmc::pores::Tessellation;

const double kXiTetrahedral = std::sqrt(1.5) - 1.0;  // paper, section IV.B
const double kXiOctahedral = std::sqrt(2.0) - 1.0;
const double kXiCubic = std::sqrt(3.0) - 1.0;

PoreOptions options_for(const Packing& p) {
  PoreOptions o;
  o.radius = p.radius;
  return o;
}

// Counts pores per (rounded) xi value; checks the tiling invariant on the way.
std::map<long, int> count_by_xi(const Packing& p, const Tessellation& t) {
  std::map<long, int> counts;
  for (const Pore& pore : t.pores()) ++counts[std::lround(pore.xi * 1e6)];
  EXPECT_NEAR(t.result().tetrahedra_volume, p.box.volume(), 1e-9 * p.box.volume());
  EXPECT_EQ(t.result().unresolved, 0u);
  return counts;
}

void expect_close_packed(const Packing& p) {
  Tessellation t(p.box, p.xyz, p.ids, options_for(p));
  const auto counts = count_by_xi(p, t);
  ASSERT_EQ(counts.size(), 2u) << "only tetrahedral and octahedral pores expected";
  EXPECT_EQ(counts.at(std::lround(kXiTetrahedral * 1e6)), static_cast<int>(2 * p.size()));
  EXPECT_EQ(counts.at(std::lround(kXiOctahedral * 1e6)), static_cast<int>(p.size()));
  for (const Pore& pore : t.pores()) {
    const bool tetrahedral = std::abs(pore.xi - kXiTetrahedral) < 1e-12;
    const bool octahedral = std::abs(pore.xi - kXiOctahedral) < 1e-12;
    EXPECT_TRUE(tetrahedral || octahedral) << "xi = " << pore.xi;
    EXPECT_EQ(pore.tetrahedra, tetrahedral ? 1 : 4);  // the octahedron: 4 tetrahedra, one pore
  }
}

TEST(PoreLattices, FccExactCoordinates) {
  expect_close_packed(pores_test::fcc(3, std::sqrt(0.5)));  // cube edge 2: integer coordinates
}

TEST(PoreLattices, FccRoundedCoordinates) {
  expect_close_packed(pores_test::fcc(4, 0.5));  // cube edge sqrt(2): every coordinate rounded
  expect_close_packed(pores_test::fcc(3, 1.37));
}

TEST(PoreLattices, FccShiftedOrigin) {
  // Pores exactly on the periodic faces (origin on a lattice site) and off them.
  Packing p = pores_test::fcc(3, 0.5);
  for (double& x : p.xyz) x += 0.1234567;
  for (int d = 0; d < 3; ++d) p.box.lo[d] += 0.1234567, p.box.hi[d] += 0.1234567;
  expect_close_packed(p);
}

TEST(PoreLattices, Hcp) {
  expect_close_packed(pores_test::hcp(3, 2, 4, 0.5));
  expect_close_packed(pores_test::hcp(4, 3, 6, 1.0));
}

TEST(PoreLattices, SimpleCubic) {
  for (double radius : {0.5, 0.8}) {
    const Packing p = pores_test::simple_cubic(4, radius);
    Tessellation t(p.box, p.xyz, p.ids, options_for(p));
    const auto counts = count_by_xi(p, t);
    ASSERT_EQ(counts.size(), 1u);
    EXPECT_EQ(counts.begin()->second, static_cast<int>(p.size()));
    for (const Pore& pore : t.pores()) {
      EXPECT_NEAR(pore.xi, kXiCubic, 1e-12);
      EXPECT_GE(pore.tetrahedra, 5);  // a cube splits into 5 or 6 tetrahedra
    }
  }
}

TEST(PoreLattices, PerturbedCloseKeepsTetrahedralAndOctahedralSizes) {
  // Perturbation delta: the tetrahedral holes are non-degenerate and stay 2 per sphere; the
  // octahedra split into several pores, all within O(delta) of the octahedral centre and size.
  const double delta = 1e-5;
  for (int seed = 1; seed <= 3; ++seed) {
    for (Packing p : {pores_test::fcc(3, 0.5), pores_test::hcp(3, 2, 4, 0.5)}) {
      pores_test::perturb(p, delta * p.radius, seed);
      Tessellation t(p.box, p.xyz, p.ids, options_for(p));
      EXPECT_NEAR(t.result().tetrahedra_volume, p.box.volume(), 1e-9 * p.box.volume());
      std::size_t tetrahedral = 0, octahedral = 0;
      double octahedral_volume = 0;
      for (const Pore& pore : t.pores()) {
        if (std::abs(pore.xi - kXiTetrahedral) < 50 * delta) ++tetrahedral;
        else if (std::abs(pore.xi - kXiOctahedral) < 50 * delta) ++octahedral, octahedral_volume += pore.volume;
        else ADD_FAILURE() << "pore xi = " << pore.xi << " is neither tetrahedral nor octahedral";
      }
      EXPECT_EQ(tetrahedral, 2 * p.size());
      EXPECT_GE(octahedral, 4 * p.size());  // split octahedra: 4 (or 5 with a sliver) pores each
      EXPECT_LE(octahedral, 5 * p.size());
      // One regular octahedron of edge 2R per sphere: volume (sqrt 2 / 3) (2R)^3.
      EXPECT_NEAR(octahedral_volume, p.size() * std::sqrt(2.0) / 3.0 * 8 * std::pow(p.radius, 3),
                  1e-3 * octahedral_volume);
    }
  }
}

TEST(PoreLattices, PerturbedSimpleCubicPoresLieOnTheCubicVoronoiSkeleton) {
  // The simple cubic Delaunay cells are cubes whose faces are squares (four concyclic centres):
  // its Voronoi edges are degenerate, so a perturbation splits them into vertices anywhere along
  // the edge joining two cube centres, with sizes from sqrt(2) - 1 (edge middle) to sqrt(3) - 1
  // (cube centre). Exact statement tested: every pore lies within O(delta) of that skeleton with
  // the size of the skeleton point there.
  const double delta = 1e-5;
  for (int seed = 1; seed <= 3; ++seed) {
    Packing p = pores_test::simple_cubic(4, 0.5);
    pores_test::perturb(p, delta * p.radius, seed);
    Tessellation t(p.box, p.xyz, p.ids, options_for(p));
    EXPECT_NEAR(t.result().tetrahedra_volume, p.box.volume(), 1e-9 * p.box.volume());
    const double a = 2 * p.radius;
    std::size_t at_cube_centres = 0;
    for (const Pore& pore : t.pores()) {
      double offset[3];  // position in the lattice cell, in units of a, lattice sites at integers
      int half = 0;
      for (int d = 0; d < 3; ++d) {
        const double u = pore.centre[d] / a;
        offset[d] = u - std::round(u);
        if (std::abs(std::abs(offset[d]) - 0.5) < 50 * delta) ++half;
      }
      ASSERT_GE(half, 2) << "pore off the skeleton at (" << pore.centre[0] << ", " << pore.centre[1] << ", "
                         << pore.centre[2] << ")";
      double along = 0.5;  // coordinate along the Voronoi edge (0.5 at a cube centre)
      for (int d = 0; d < 3; ++d)
        if (std::abs(std::abs(offset[d]) - 0.5) >= 50 * delta) along = offset[d];
      const double expected = 2.0 * std::sqrt(0.5 + along * along) - 1.0;
      EXPECT_NEAR(pore.xi, expected, 100 * delta);
      if (std::abs(pore.xi - kXiCubic) < 100 * delta) ++at_cube_centres;
    }
    EXPECT_GE(at_cube_centres, p.size());  // every cube still has at least one vertex near its centre
  }
}

}  // namespace
