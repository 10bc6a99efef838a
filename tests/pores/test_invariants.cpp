// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Invariants on random packings over many seeds: empty spheres (brute force), tiling of the
// periodic box, each pore once, x-y periodic vs triply periodic agreement, overlaps, P0 queries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "pores_test_util.h"
#include "tapmc_pores/analysis.h"
#include "tapmc_pores/tessellation.h"

namespace {

using pores_test::Packing;
using tapmc::pores::OverlapError;
using tapmc::pores::Pore;
using tapmc::pores::PoreOptions;
using tapmc::pores::Tessellation;

PoreOptions options_for(const Packing& p) {
  PoreOptions o;
  o.radius = p.radius;
  return o;
}

// Brute force: the pore sphere touches its four spheres and contains no centre (any image).
void expect_empty_spheres(const Packing& p, const Tessellation& t) {
  const double tol = 1e-9 * p.radius;
  for (const Pore& pore : t.pores()) {
    const double r = (1.0 + pore.xi) * p.radius;
    double nearest = 1e300;
    for (std::size_t j = 0; j < p.size(); ++j)
      nearest = std::min(nearest, pores_test::distance(p.box, pore.centre.data(), &p.xyz[3 * j]));
    EXPECT_NEAR(nearest, r, tol) << "pore sphere not empty or not touching";
    for (std::int64_t id : pore.ids)
      EXPECT_NEAR(pores_test::distance(p.box, pore.centre.data(), &p.xyz[3 * (id - 1)]), r, tol);
    for (int d = 0; d < 3; ++d)
      if (p.box.periodic[d]) {
        EXPECT_GE(pore.centre[d], p.box.lo[d]);
        EXPECT_LT(pore.centre[d], p.box.hi[d]);
      }
  }
}

// No two pores are the same Voronoi vertex (same centre up to periodicity).
void expect_distinct(const Packing& p, const Tessellation& t) {
  std::set<std::array<std::int64_t, 4>> tetrahedra;
  for (const Pore& pore : t.pores()) EXPECT_TRUE(tetrahedra.insert(pore.ids).second || pore.tetrahedra > 1);
  const auto& pores = t.pores();
  std::vector<std::size_t> order(pores.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pores[a].centre[0] < pores[b].centre[0]; });
  // Sweep in x (plus the periodic seam) for centres closer than 1e-7 R.
  const double eps = 1e-7 * p.radius;
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size() && pores[order[b]].centre[0] - pores[order[a]].centre[0] < eps; ++b)
      EXPECT_GT(pores_test::distance(p.box, pores[order[a]].centre.data(), pores[order[b]].centre.data()), eps);
}

TEST(PoreInvariants, RandomTriplyPeriodicPackings) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Packing p = pores_test::random_packing(250, 8.0, {true, true, true}, seed);
    ASSERT_EQ(p.size(), 250u);
    const Tessellation t(p.box, p.xyz, p.ids, options_for(p));
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_NEAR(t.result().tetrahedra_volume, p.box.volume(), 1e-9 * p.box.volume());
    EXPECT_EQ(t.result().unresolved, 0u);
    // Random centres are in general position: no degenerate vertex, one tetrahedron per pore.
    EXPECT_EQ(t.result().tetrahedra, t.result().pore_count);
    expect_empty_spheres(p, t);
    expect_distinct(p, t);
  }
}

TEST(PoreInvariants, RandomSlabsPeriodicInXYOnly) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Packing p = pores_test::random_packing(250, 8.0, {true, true, false}, seed);
    const Tessellation t(p.box, p.xyz, p.ids, options_for(p));
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_empty_spheres(p, t);
    expect_distinct(p, t);
  }
}

// A pore whose empty sphere lies inside [zlo, zhi] cannot see z images: the x-y periodic and the
// triply periodic analyses of the same centres must agree on exactly those pores (none missed,
// none doubled at the x/y seams).
TEST(PoreInvariants, SlabAgreesWithTriplyPeriodicAwayFromZFaces) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    Packing slab = pores_test::random_packing(250, 8.0, {true, true, false}, seed);
    Packing bulk = slab;
    bulk.box.periodic = {true, true, true};
    const Tessellation ts(slab.box, slab.xyz, slab.ids, options_for(slab));
    const Tessellation tb(bulk.box, bulk.xyz, bulk.ids, options_for(bulk));
    auto interior = [&](const Tessellation& t) {
      std::map<std::array<std::int64_t, 4>, double> pores;
      for (const Pore& pore : t.pores()) {
        const double r = (1 + pore.xi) * slab.radius;
        if (pore.centre[2] - r > slab.box.lo[2] && pore.centre[2] + r < slab.box.hi[2]) pores[pore.ids] = pore.xi;
      }
      return pores;
    };
    const auto a = interior(ts), b = interior(tb);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_GT(a.size(), 500u);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [ids, xi] : a) {
      const auto it = b.find(ids);
      ASSERT_NE(it, b.end());
      EXPECT_NEAR(it->second, xi, 1e-10);
    }
  }
}

TEST(PoreInvariants, SparsePackingsGrowThePaddingUntilExact) {
  // 40 spheres in an 8^3 periodic box: empty spheres wider than the default padding allows.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Packing p = pores_test::random_packing(40, 8.0, {true, true, true}, seed);
    PoreOptions wide = options_for(p);
    wide.padding_over_radius = 16.0;
    const Tessellation adaptive(p.box, p.xyz, p.ids, options_for(p)), reference(p.box, p.xyz, p.ids, wide);
    SCOPED_TRACE("seed " + std::to_string(seed));
    EXPECT_GT(adaptive.result().attempts, 1);
    EXPECT_EQ(adaptive.result().unresolved, 0u);
    EXPECT_NEAR(adaptive.result().tetrahedra_volume, p.box.volume(), 1e-9 * p.box.volume());
    std::map<std::array<std::int64_t, 4>, double> a, b;
    for (const Pore& pore : adaptive.pores()) a[pore.ids] = pore.xi;
    for (const Pore& pore : reference.pores()) b[pore.ids] = pore.xi;
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [ids, xi] : a) {
      const auto it = b.find(ids);
      ASSERT_NE(it, b.end());
      EXPECT_NEAR(it->second, xi, 1e-12);  // same cell, vertices possibly in another order
    }
    expect_empty_spheres(p, adaptive);
  }
}

TEST(PoreInvariants, DegenerateInputIsRefusedOrHandled) {
  // A flat layer (non-periodic z): no tetrahedra at all.
  Packing layer;
  layer.box.lo = {0, 0, 0};
  layer.box.hi = {6, 6, 2};
  layer.box.periodic = {true, true, false};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) layer.add(i + 0.5, j + 0.5, 1.0);
  EXPECT_THROW(Tessellation(layer.box, layer.xyz, layer.ids, options_for(layer)), std::runtime_error);
  // Two spheres in a periodic box: their periodic Delaunay cells repeat a sphere (no simplicial
  // tiling exists), refused with a message.
  Packing pair;
  pair.box.lo = {0, 0, 0};
  pair.box.hi = {5, 5, 5};
  pair.add(1.0, 1.2, 1.4);
  pair.add(3.1, 2.9, 3.7);
  EXPECT_THROW(Tessellation(pair.box, pair.xyz, pair.ids, options_for(pair)), std::runtime_error);
  // Sparse (30 spheres in 10^3): the padding grows until the box is tiled exactly; with the
  // growth forbidden (no retry): refused, never a partial answer.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Packing sparse = pores_test::random_packing(30, 10.0, {true, true, true}, seed);
    const Tessellation t(sparse.box, sparse.xyz, sparse.ids, options_for(sparse));
    EXPECT_NEAR(t.result().tetrahedra_volume, sparse.box.volume(), 1e-9 * sparse.box.volume());
    EXPECT_GT(t.result().attempts, 1);
    EXPECT_EQ(t.result().unresolved, 0u);
    expect_empty_spheres(sparse, t);
    PoreOptions fixed = options_for(sparse);
    fixed.max_padding_retries = 0;
    EXPECT_THROW(Tessellation(sparse.box, sparse.xyz, sparse.ids, fixed), std::runtime_error);
  }
  // Four spheres in a 100^3 periodic box: cells no padding can resolve. Refused (was a result
  // of 0 pores, or with a wide padding 5 of 17 pores and nu = 9e5).
  Packing four;
  four.box.lo = {0, 0, 0};
  four.box.hi = {100, 100, 100};
  const double centres[4][3] = {{1, 1, 1}, {5, 5, 5}, {2, 7, 3}, {8, 2, 6}};
  for (const auto& c : centres) four.add(c[0], c[1], c[2]);
  for (double padding : {8.0, 32.0}) {
    PoreOptions o = options_for(four);
    o.padding_over_radius = padding;
    EXPECT_THROW(Tessellation(four.box, four.xyz, four.ids, o), std::runtime_error) << padding;
  }
}

TEST(PoreInvariants, OverlapAcrossThePeriodicSeamIsRefused) {
  Packing p = pores_test::random_packing(60, 6.0, {true, true, true}, 7);
  p.add(0.02, 3.0, 3.0);
  p.add(5.99, 3.0, 3.3);  // 0.3 from the previous one through the x faces
  try {
    const Tessellation t(p.box, p.xyz, p.ids, options_for(p));
    FAIL() << "overlap not detected";
  } catch (const OverlapError& e) {
    const std::set<std::size_t> pair{e.index_a, e.index_b};
    EXPECT_TRUE(pair.count(p.size() - 1) || pair.count(p.size() - 2)) << e.what();
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos);
  }
}

TEST(PoreInvariants, OverlapRefusalNamesTheDeepestPairAndTheThreshold) {
  // Three overlapping pairs of different depths (1 %, 5 %, 2 % of a diameter) in a loose
  // packing: the deepest is named, whatever the order of the cells.
  for (int seed : {1, 2, 3}) {
    const Packing p = pores_test::random_packing(80, 9.0, {true, true, false}, seed);
    const double depths[3] = {0.01, 0.05, 0.02};
    Packing q;  // the three pairs first (ids 1-6), then the spheres that overlap none of them
    q.box = p.box;
    q.radius = p.radius;
    for (int k = 0; k < 3; ++k) {
      q.add(1.5 + 3.0 * k, 4.5, 4.5);
      q.add(1.5 + 3.0 * k + 2 * p.radius * (1 - depths[k]), 4.5, 4.5);
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      bool clear = true;
      for (std::size_t j = 0; j < 6 && clear; ++j)
        clear = pores_test::distance(p.box, &p.xyz[3 * i], &q.xyz[3 * j]) >= 2 * p.radius;
      if (clear) q.add(p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]);
    }
    PoreOptions o = options_for(q);
    try {
      const Tessellation t(q.box, q.xyz, q.ids, o);
      FAIL() << "overlaps not detected";
    } catch (const OverlapError& e) {
      const std::set<std::size_t> pair{e.index_a, e.index_b};
      EXPECT_EQ(pair, (std::set<std::size_t>{2, 3})) << e.what();
      EXPECT_NEAR(e.depth, 0.05, 1e-12);
      EXPECT_NEAR(e.distance, 0.95, 1e-12);
      EXPECT_NEAR(e.threshold, 1.0 * (1 - o.overlap_tolerance), 1e-15);
      EXPECT_EQ(e.pairs, 3u);
      const std::string what = e.what();
      EXPECT_NE(what.find("spheres 3 and 4 overlap by 5 % of a diameter"), std::string::npos) << what;
      EXPECT_NE(what.find("the deepest of 3 overlapping pairs"), std::string::npos) << what;
      EXPECT_NE(what.find("2R (1 - 0.001) = 0.999"), std::string::npos) << what;
    }
    // A tolerance above the deepest overlap accepts the packing.
    o.overlap_tolerance = 0.051;
    EXPECT_NO_THROW(Tessellation(q.box, q.xyz, q.ids, o));
    o.overlap_tolerance = 0.049;
    EXPECT_THROW(Tessellation(q.box, q.xyz, q.ids, o), OverlapError);
  }
}

// The refusal of the pair {a, b} (input positions) at `distance`; a failure when accepted.
std::string overlap_refusal(const Packing& p, std::size_t a, std::size_t b, double distance) {
  try {
    const Tessellation t(p.box, p.xyz, p.ids, options_for(p));
  } catch (const OverlapError& e) {
    EXPECT_EQ(std::set<std::size_t>({e.index_a, e.index_b}), std::set<std::size_t>({a, b})) << e.what();
    EXPECT_NEAR(e.distance, distance, 1e-6 * distance) << e.what();
    EXPECT_NEAR(e.depth, 1.0, 1e-8);
    return e.what();
  }
  ADD_FAILURE() << "spheres " << p.ids[a] << " and " << p.ids[b] << " at distance " << distance << " accepted";
  return "";
}

TEST(PoreInvariants, ADuplicatedSphereIsRefusedLikeANearOne) {
  // 4096 spheres (simple cubic, triply periodic) and a copy of sphere 1000 as atom 4097. CGAL's
  // Delaunay merges coincident points: the copy vanished and the pores were those of 4096.
  Packing p = pores_test::simple_cubic(16, 0.5);
  const std::size_t copied = 999;
  p.add(p.xyz[3 * copied], p.xyz[3 * copied + 1], p.xyz[3 * copied + 2]);
  ASSERT_EQ(p.size(), 4097u);
  std::ostringstream at;
  at.precision(10);
  at << "both are at (" << p.xyz[3 * copied] << ", " << p.xyz[3 * copied + 1] << ", " << p.xyz[3 * copied + 2] << ")";
  const std::string duplicate = overlap_refusal(p, copied, 4096, 0.0);
  EXPECT_NE(duplicate.find("spheres 1000 and 4097 overlap by 100 % of a diameter (centre distance 0, 2R = 1): " + at.str() +
                           "; pairs closer than 2R (1 - 0.001) = 0.999 are refused"),
            std::string::npos)
      << duplicate;
  // The same copy 1e-9 away: the same pair, the same message family.
  p.xyz[3 * 4096] += 1e-9;
  const std::string near = overlap_refusal(p, copied, 4096, p.xyz[3 * 4096] - p.xyz[3 * copied]);
  EXPECT_NE(near.find("spheres 1000 and 4097 overlap by 100 % of a diameter (centre distance 1e-09, 2R = 1)"),
            std::string::npos)
      << near;
  // Two spheres copied in a slab (walls in z), the one nearest a periodic face (its images are
  // copied too) then sphere 5: the lowest pair is named, with the count of coinciding pairs.
  Packing slab = pores_test::random_packing(150, 7.0, {true, true, false}, 3);
  std::size_t edge = 0;
  for (std::size_t i = 0; i < slab.size(); ++i)
    if (slab.xyz[3 * i] < slab.xyz[3 * edge]) edge = i;
  ASSERT_NE(edge, 5u);
  for (std::size_t copy : {edge, std::size_t{5}})
    slab.add(slab.xyz[3 * copy], slab.xyz[3 * copy + 1], slab.xyz[3 * copy + 2]);
  const auto [a, b] = edge < 5 ? std::pair<std::size_t, std::size_t>{edge, 150} : std::pair<std::size_t, std::size_t>{5, 151};
  const std::string two = overlap_refusal(slab, a, b, 0.0);
  EXPECT_NE(two.find("spheres " + std::to_string(a + 1) + " and " + std::to_string(b + 1) +
                     " overlap by 100 % of a diameter (centre distance 0"),
            std::string::npos)
      << two;
  EXPECT_NE(two.find("the first of 2 coinciding pairs"), std::string::npos) << two;
}

TEST(PoreInvariants, ContactWithinToleranceIsAccepted) {
  Packing p = pores_test::fcc(3, 0.5);
  p.xyz[0] += 1e-6;  // pushes sphere 1 into its neighbour by 1e-6 of a diameter
  EXPECT_NO_THROW(Tessellation(p.box, p.xyz, p.ids, options_for(p)));
}

TEST(PoreInvariants, BadArgumentsThrow) {
  const Packing p = pores_test::fcc(2, 0.5);
  PoreOptions o = options_for(p);
  o.radius = -1;
  EXPECT_THROW(Tessellation(p.box, p.xyz, p.ids, o), std::invalid_argument);
  std::vector<double> short_xyz(p.xyz.begin(), p.xyz.end() - 1);
  EXPECT_THROW(Tessellation(p.box, short_xyz, p.ids, options_for(p)), std::invalid_argument);
}

TEST(PoreInvariants, APaddingOfTooManyBoxLengthsIsRefusedWhateverItsSize) {
  // The count of image layers was converted to int before it was checked: a padding of 1e15 R
  // wrapped around, and the tool answered with the pores of a wrong triangulation (exit code 0).
  const Packing p = pores_test::fcc(2, 0.5);
  for (double padding : {1e3, 1e15, 1e300, std::numeric_limits<double>::infinity()}) {
    PoreOptions o = options_for(p);
    o.padding_over_radius = padding;
    try {
      const Tessellation t(p.box, p.xyz, p.ids, o);
      ADD_FAILURE() << "padding " << padding << " R accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("is over 100 box lengths: the periodic box is far too small for R"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(PoreInvariants, NearestCentreDistancesMatchBruteForce) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (const std::array<bool, 3> periodic : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, true, false}}) {
      const Packing p = pores_test::random_packing(200, 7.0, periodic, seed);
      const Tessellation t(p.box, p.xyz, p.ids, options_for(p));
      tapmc::pores::Region whole{p.box.lo, p.box.hi};
      const auto points = tapmc::pores::random_points(whole, 500, seed, 0);
      const auto distances = t.nearest_centre_distances(points);
      for (std::size_t i = 0; i < 500; ++i) {
        double nearest = 1e300;
        for (std::size_t j = 0; j < p.size(); ++j)
          nearest = std::min(nearest, pores_test::distance(p.box, &points[3 * i], &p.xyz[3 * j]));
        EXPECT_NEAR(distances[i], nearest, 1e-12);
      }
    }
  }
}

}  // namespace
