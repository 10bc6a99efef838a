// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the redeposition kernel (Settler): exact geometry, invariants, brute-force oracles.
#include "settle_test_scenes.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_settle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;

namespace {

constexpr double kTol = defaults::kContactTolerance;

void expect_valid(const Scene &s, const std::string &what)
{
  const OracleReport rep = brute_force_check(s.xyz.data(), s.radius.data(), s.size(), s.box, kTol);
  EXPECT_EQ(rep.pair_overlaps, 0) << what << " worst gap " << rep.worst_gap;
  EXPECT_EQ(rep.plane_violations, 0) << what << " worst gap " << rep.worst_gap;
  const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), s.size(), s.box, kTol);
  EXPECT_EQ(v.i, -1) << what << " find_violation: " << v.i << " " << v.j << " gap " << v.gap;
}

double mean_height(const Scene &s)
{
  double sum = 0;
  for (int i = 0; i < s.size(); ++i) sum += s.xyz[3 * i + 2] - s.box.floor_z;
  return sum / s.size();
}

}  // namespace

// Many seeds, PBC and FBC, mono and poly: the settled packing has no overlap (brute force, all
// images), every sphere stays in the box, no sphere ever ends higher than it started, and <Z>
// drops from the dilute start.
TEST(Settle, NoViolationsAfterSettlingAllBoundariesAndRadii)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (int poly = 0; poly < 2; ++poly)
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const std::string what = variant_name(periodic, poly, seed);
        Scene s = dilute_lattice(250, 9.0, 0.5, periodic, poly, seed);
        const std::vector<double> start = s.xyz;
        Settler settler;
        SettleParams p = paper_params(0.5, seed, 7, 1e-300, 60);
        const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
        expect_valid(s, what);
        EXPECT_EQ(res.trials, 60L * 250) << what;
        EXPECT_GT(res.accepted, 0) << what;
        EXPECT_LT(res.mean_height, res.mean_height_start) << what;
        EXPECT_NEAR(res.mean_height, mean_height(s), 1e-12) << what;
        for (int i = 0; i < s.size(); ++i) {
          EXPECT_LE(s.xyz[3 * i + 2], start[3 * i + 2]) << what << " sphere " << i << " went up";
          for (int d = 0; d < 2; ++d) {
            EXPECT_GE(s.xyz[3 * i + d], 0.0) << what;
            EXPECT_LT(s.xyz[3 * i + d], 9.0) << what;
          }
        }
      }
}

TEST(Settle, SweepOrderAlsoKeepsGeometryExact)
{
  for (int periodic = 0; periodic < 2; ++periodic) {
    Scene s = dilute_lattice(200, 8.0, 0.5, periodic, true, 11);
    Settler settler;
    SettleParams p = paper_params(0.5, 3, 4, 1e-300, 50);
    p.order = PickOrder::Sweep;
    const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    expect_valid(s, periodic ? "sweep PBC" : "sweep FBC");
    EXPECT_LT(res.mean_height, res.mean_height_start);
  }
}

// A lone sphere falls onto the floor: z -> R from above, never below the tolerance.
TEST(Settle, LoneSphereFallsOntoTheFloor)
{
  Scene s;
  s.box = make_box(10.0, true);
  s.xyz = {5.0, 5.0, 8.0};
  s.radius = {1.0};
  Settler settler;
  // Checks every 5000 trials: a single rejected trial must not count as convergence.
  SettleParams p = paper_params(1.0, 5, 1, 1e-9, 1000);
  p.check_interval = 5000;
  const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, 1, s.box, p);
  EXPECT_FALSE(res.hit_cap);
  EXPECT_GE(s.xyz[2], 1.0 - 2.0 * kTol);
  EXPECT_LT(s.xyz[2] - 1.0, 1e-4);
  EXPECT_NEAR(res.mean_height, s.xyz[2], 1e-15);
}

// A sphere above a fixed sphere in a walled column 2.1 R wide cannot pass it: it comes down
// onto the fixed sphere and stays on it, never below the lowest legal point of the column,
// z* = R + sqrt(4 - 2 * 0.05^2) R (resting on the sphere in a corner of the column). Near the
// apex almost every downward move is blocked, so it need not reach z* (the model's physics).
// Two unit spheres placed at exact contact in random directions, at coordinates of magnitude z:
// up to largest_exact_coordinate the rounding of the positions never makes the contact an
// overlap beyond the tolerance; a hundred times farther out it does (the control).
TEST(Settle, ContactsResolveUpToTheLargestExactCoordinate)
{
  const double bound = largest_exact_coordinate(1.0);
  EXPECT_NEAR(bound, 1.126e5, 1e3);
  std::mt19937_64 bits(5);
  std::normal_distribution<double> gauss;
  auto false_overlaps = [&](double z) {
    int count = 0;
    for (int k = 0; k < 20000; ++k) {
      double u[3] = {gauss(bits), gauss(bits), gauss(bits)};
      const double norm = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double pi[3] = {z, -z, z};
      double pj[3];
      for (int d = 0; d < 3; ++d) pj[d] = pi[d] + u[d] / norm;
      const double r2 = distance_sq(pj[0] - pi[0], pj[1] - pi[1], pj[2] - pi[2]);
      if (r2 < overlap_threshold_sq(0.5, 0.5, 1.0 - defaults::kContactTolerance)) ++count;
    }
    return count;
  };
  EXPECT_EQ(false_overlaps(bound), 0);
  EXPECT_GT(false_overlaps(100.0 * bound), 1000);
}

TEST(Settle, SphereCannotPassThroughAFixedSphere)
{
  Scene s;
  s.box = make_box(2.1, false);
  s.xyz = {1.05, 1.05, 1.0, 1.05, 1.05, 4.5};
  s.radius = {1.0, 1.0};
  const unsigned char movable[2] = {0, 1};
  Settler settler;
  SettleParams p = paper_params(1.0, 9, 1, 1e-10, 1000);
  p.check_interval = 5000;
  settler.settle(s.xyz.data(), s.radius.data(), movable, 2, s.box, p);
  EXPECT_EQ(s.xyz[0], 1.05);
  EXPECT_EQ(s.xyz[2], 1.0);
  const double rest = 1.0 + std::sqrt(4.0 - 2 * 0.05 * 0.05);
  EXPECT_GE(s.xyz[5], rest - 1e-9);
  const double dist = std::sqrt(std::pow(s.xyz[3] - 1.05, 2) + std::pow(s.xyz[4] - 1.05, 2) +
                                std::pow(s.xyz[5] - 1.0, 2));
  EXPECT_LT(dist - 2.0, 1e-3);  // resting on the fixed sphere
  expect_valid(s, "column");
}

// Periodic square of side 2R over a fixed sphere: its images tile the floor, and the movable
// sphere ends in the hollow of four at height (1 + sqrt 2) R above... the floor, corner (0,0).
TEST(Settle, SphereComesToRestInTheHollowOfFourPeriodicImages)
{
  Scene s;
  s.box = make_box(2.0, true);
  s.xyz = {1.0, 1.0, 1.0, 0.6, 0.7, 5.0};
  s.radius = {1.0, 1.0};
  const unsigned char movable[2] = {0, 1};
  Settler settler;
  SettleParams p = paper_params(1.0, 21, 1, 1e-10, 1000);
  p.check_interval = 5000;
  settler.settle(s.xyz.data(), s.radius.data(), movable, 2, s.box, p);
  const double hollow = 1.0 + std::sqrt(2.0);
  EXPECT_GE(s.xyz[5], hollow - 1e-9);
  EXPECT_LT(s.xyz[5], hollow + 1e-3);
  // The hollow is at the corner (0, 0) == (2, 2) of the periodic square.
  const double ex = std::min(s.xyz[3], 2.0 - s.xyz[3]), ey = std::min(s.xyz[4], 2.0 - s.xyz[4]);
  EXPECT_LT(std::hypot(ex, ey), 0.05);
  expect_valid(s, "hollow");
}

namespace {

// FCC at contact, cubic cell a = 2 sqrt(2) R, periodic in x, y (cells x cells), `layers`
// half-cell layers on the floor; every sphere rests in a hollow of four.
Scene fcc_at_contact(int cells, int layers, double r)
{
  Scene s;
  const double a = 2.0 * std::sqrt(2.0) * r;
  s.box = make_box(cells * a, true);
  for (int l = 0; l < layers; ++l)
    for (int i = 0; i < cells; ++i)
      for (int j = 0; j < cells; ++j)
        for (int b = 0; b < 2; ++b) {
          // even layers: (0, 0), (1/2, 1/2); odd layers: (1/2, 0), (0, 1/2) of the cell
          const double ox = (l % 2 == 0) ? 0.5 * b : 0.5 * (1 - b), oy = 0.5 * b;
          s.xyz.push_back((i + ox) * a + 0.25 * a);
          s.xyz.push_back((j + oy) * a + 0.25 * a);
          s.xyz.push_back(r + l * 0.5 * a);
          s.radius.push_back(r);
        }
  return s;
}

// Simple cubic at contact on the floor, spacing 2R, in a walled or periodic box.
Scene simple_cubic_at_contact(int side, int layers, double r, bool periodic)
{
  Scene s;
  s.box = make_box(side * 2.0 * r, periodic);
  for (int l = 0; l < layers; ++l)
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        s.xyz.insert(s.xyz.end(), {(2 * i + 1) * r, (2 * j + 1) * r, (2 * l + 1) * r});
        s.radius.push_back(r);
      }
  return s;
}

double max_displacement(const Scene &a, const std::vector<double> &before)
{
  double m = 0;
  for (std::size_t k = 0; k < before.size(); ++k) m = std::max(m, std::fabs(a.xyz[k] - before[k]));
  return m;
}

}  // namespace

// Exact lattices at contact are legal input, and settling them accepts no real move: every
// sphere is caged (FCC: hollow of four below, contacts around; simple cubic: floor / sphere
// below and four side contacts), so nothing moves by more than the contact tolerance.
TEST(Settle, ExactLatticesAtContactAreLegalAndStayPut)
{
  const double r = 0.7;
  std::vector<Scene> scenes = {fcc_at_contact(4, 6, r), simple_cubic_at_contact(5, 4, r, true),
                               simple_cubic_at_contact(5, 4, r, false)};
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    Scene &s = scenes[k];
    const std::string what = "lattice " + std::to_string(k);
    expect_valid(s, what + " input");
    const std::vector<double> before = s.xyz;
    Settler settler;
    SettleParams p = paper_params(r, 100 + k, 5, 1e-300, 30);
    settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    expect_valid(s, what + " after");
    EXPECT_LE(max_displacement(s, before), 10 * kTol * r) << what;
  }
}

// The lattices' neighbours really are at contact: pushing one sphere 1e-6 R towards a
// neighbour (across the periodic boundary for the first sphere) is detected.
TEST(Settle, FindViolationSeesAContactPushedInAcrossTheBoundary)
{
  Scene s = simple_cubic_at_contact(4, 2, 1.0, true);
  // Sphere 0 at (1, 1, 1); its -x neighbour is the image of sphere 12 at (7 - 8, 1, 1).
  s.xyz[0] -= 1e-6;
  const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), s.size(), s.box, kTol);
  ASSERT_NE(v.i, -1);
  EXPECT_TRUE((v.i == 0 && v.j == 12) || (v.i == 12 && v.j == 0)) << v.i << " " << v.j;
  EXPECT_NEAR(v.gap, -1e-6, 1e-12);
  // The same push without periodic images is legal (the wall is at x = 0, the sphere was
  // 1 R from it): but pushing it past the wall is a wall violation.
  Scene w = simple_cubic_at_contact(4, 2, 1.0, false);
  w.xyz[0] -= 1e-6;
  const Violation vw = Settler::find_violation(w.xyz.data(), w.radius.data(), w.size(), w.box, kTol);
  EXPECT_EQ(vw.i, 0);
  EXPECT_EQ(vw.j, -2);
  EXPECT_NEAR(vw.gap, -1e-6, 1e-12);
}

TEST(Settle, ImmovableSpheresNeverMove)
{
  for (int periodic = 0; periodic < 2; ++periodic) {
    Scene s = dilute_lattice(300, 9.0, 0.5, periodic, true, 31);
    std::vector<unsigned char> movable(s.size());
    for (int i = 0; i < s.size(); ++i) movable[i] = (i % 3 != 0);
    const std::vector<double> before = s.xyz;
    Settler settler;
    const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), movable.data(), s.size(),
                                            s.box, paper_params(0.5, 2, 3, 1e-300, 40));
    EXPECT_EQ(res.movable, 200);
    for (int i = 0; i < s.size(); ++i) {
      if (movable[i]) continue;
      for (int d = 0; d < 3; ++d) EXPECT_EQ(std::memcmp(&s.xyz[3 * i + d], &before[3 * i + d], 8), 0);
    }
    expect_valid(s, "mask");
  }
}

TEST(Settle, DeterministicForSameKeysDifferentOtherwise)
{
  const Scene start = dilute_lattice(200, 8.0, 0.5, true, true, 41);
  auto run = [&](std::uint64_t seed, std::uint64_t stream, PickOrder order) {
    Scene s = start;
    SettleParams p = paper_params(0.5, seed, stream, 1e-300, 20);
    p.order = order;
    Settler settler;
    settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
    return s.xyz;
  };
  for (PickOrder order : {PickOrder::Random, PickOrder::Sweep}) {
    const std::vector<double> a = run(1, 1, order), b = run(1, 1, order);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
    EXPECT_NE(a, run(2, 1, order));
    EXPECT_NE(a, run(1, 2, order));
  }
  // A reused Settler (cached sampler and grid) gives the same bits as a fresh one.
  Settler reused;
  Scene s1 = start, s2 = start;
  SettleParams p = paper_params(0.5, 1, 1, 1e-300, 20);
  reused.settle(s1.xyz.data(), s1.radius.data(), nullptr, s1.size(), s1.box, p);
  reused.settle(s2.xyz.data(), s2.radius.data(), nullptr, s2.size(), s2.box, p);
  EXPECT_EQ(s1.xyz, s2.xyz);
  EXPECT_EQ(s1.xyz, run(1, 1, PickOrder::Random));
}

// Convergence bookkeeping: trials = checks * interval; the cap is reported.
TEST(Settle, CheckIntervalAndCapAreHonoured)
{
  Scene s = dilute_lattice(100, 8.0, 0.5, true, false, 51);
  Settler settler;
  SettleParams p = paper_params(0.5, 1, 1, 1e-300, 7);
  p.check_interval = 33;
  const SettleResult capped = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
  EXPECT_TRUE(capped.hit_cap);
  EXPECT_EQ(capped.checks, 7);
  EXPECT_EQ(capped.trials, 7 * 33);
  // A generous eta stops at the first check whose relative change of <Z> is below it (spheres
  // resting on the floor: every move is blocked, nothing falls).
  Scene resting;
  resting.box = s.box;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      resting.xyz.insert(resting.xyz.end(), {i + 0.5, j + 0.5, 0.5});
      resting.radius.push_back(0.5);
    }
  p.eta = 0.5;
  const SettleResult quick = settler.settle(resting.xyz.data(), resting.radius.data(), nullptr,
                                            resting.size(), resting.box, p);
  EXPECT_FALSE(quick.hit_cap);
  EXPECT_EQ(quick.checks, 1);
  EXPECT_EQ(quick.trials, 33);
}

// A packing in free fall is never reported converged, however small its relative change of
// <Z> per sweep: a sphere 1e7 radii up loses ~1e-8 of its height per trial, far below eta, but
// accepts every trial, and must run to the cap; once it rests on the floor (every trial
// rejected), the same eta stops it at the first check.
TEST(Settle, FreeFallIsNeverConverged)
{
  Scene s;
  s.box = make_box(10.0, true);
  s.xyz = {5.0, 5.0, 1e7};
  s.radius = {1.0};
  Settler settler;
  SettleParams p = paper_params(1.0, 5, 1, 1e-6, 50);
  const SettleResult high = settler.settle(s.xyz.data(), s.radius.data(), nullptr, 1, s.box, p);
  EXPECT_TRUE(high.hit_cap);
  EXPECT_EQ(high.checks, 50);
  EXPECT_LT(s.xyz[2], 1e7);
  s.xyz[2] = 1.0;
  const SettleResult resting = settler.settle(s.xyz.data(), s.radius.data(), nullptr, 1, s.box, p);
  EXPECT_FALSE(resting.hit_cap);
  EXPECT_EQ(resting.checks, 1);
}

// A redeposition after a small tap converges with the paper's criterion, and the packing
// stays exact; the settled bed (sedimented from a loose random gas) is a random loose packing,
// far denser than the start (0.3) and below random close packing (0.64).
TEST(Settle, RedepositionAfterTapConverges)
{
  Scene s = settled_bed(512, 8.0, 0.5, true, false, 61, 300);
  expect_valid(s, "bed");
  const double phi = slab_fraction(s, 0.5, 3.5);
  EXPECT_GT(phi, 0.45);
  EXPECT_LT(phi, 0.64);
  dilate(s, 0.01);
  Settler settler;
  const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box,
                                          paper_params(0.5, 1, 77, 1e-4, 10000));
  EXPECT_FALSE(res.hit_cap);
  EXPECT_LT(res.mean_height, res.mean_height_start);
  expect_valid(s, "after tap");
}

// Small spheres (R = 0.1) with one big one (R = 1) that sizes the lists' skin (0.2 R_max): the
// small spheres fall freely, so their lists are remade locally many times mid-run; the geometry
// stays exact and the run deterministic.
TEST(Settle, ManyListUpdatesMidRunKeepGeometryAndDeterminism)
{
  Scene s = dilute_lattice(300, 6.0, 1.0, true, false, 71);
  for (int i = 1; i < s.size(); ++i) s.radius[i] = 0.1;
  const Scene start = s;
  Settler settler;
  SettleParams p = paper_params(1.0, 4, 4, 1e-300, 150);
  const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
  EXPECT_GT(res.list_updates, 20);
  expect_valid(s, "updates");
  Scene again = start;
  Settler other;
  other.settle(again.xyz.data(), again.radius.data(), nullptr, again.size(), again.box, p);
  EXPECT_EQ(again.xyz, s.xyz);
}

// The neighbour lists are exact: their skin changes how often they are remade, never which
// moves are accepted. Skins from 0.01 R_max (an update almost every accepted move) to 3 R_max
// (lists of many neighbours, few updates) give bit-identical positions and image shifts, in a
// normal periodic box, with walls, and in a periodic box narrower than the list radius (one
// cell across: every sphere is met through several images by the cell query).
TEST(Settle, VerletSkinNeverChangesTheResult)
{
  struct Case {
    Scene start;
    const char *name;
  };
  const std::vector<Case> cases = {{dilute_lattice(200, 8.0, 0.5, true, true, 91), "pbc poly"},
                                   {dilute_lattice(200, 8.0, 0.5, false, false, 92), "walls mono"},
                                   {dilute_lattice(30, 2.4, 1.0, true, true, 93), "narrow pbc"}};
  for (const Case &c : cases) {
    SCOPED_TRACE(c.name);
    const SettleParams p = paper_params(0.5, 5, 6, 1e-300, 200);
    std::vector<std::vector<double>> xyz;
    std::vector<std::vector<int>> images;
    std::vector<long> updates;
    for (double skin : {0.01, 0.2, 3.0}) {
      Scene s = c.start;
      std::vector<int> image(2 * s.size(), 0);
      Settler settler;
      settler.set_verlet_skin(skin);
      const SettleResult res =
          settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p, image.data());
      EXPECT_GT(res.accepted, 0);
      expect_valid(s, c.name);
      xyz.push_back(s.xyz);
      images.push_back(image);
      updates.push_back(res.list_updates);
    }
    EXPECT_EQ(xyz[0], xyz[1]);
    EXPECT_EQ(xyz[0], xyz[2]);
    EXPECT_EQ(images[0], images[1]);
    EXPECT_EQ(images[0], images[2]);
    EXPECT_GT(updates[0], updates[2]);
  }
  Settler settler;
  EXPECT_THROW(settler.set_verlet_skin(0.0), std::invalid_argument);
  EXPECT_THROW(settler.set_verlet_skin(std::nan("")), std::invalid_argument);
}

// Image shifts: spheres leaving through a periodic side come back wrapped, with the period
// count reported so unwrapped trajectories stay continuous.
TEST(Settle, WrapsAreCountedAsImageShifts)
{
  Scene s = dilute_lattice(150, 6.0, 0.5, true, false, 81);
  const std::vector<double> before = s.xyz;
  std::vector<int> image(2 * s.size(), 0);
  Settler settler;
  SettleParams p = paper_params(0.5, 1, 1, 1e-300, 100);
  p.theta0 = 1.5;  // wide: lots of sideways motion
  p.d_max = 0.3;
  settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p, image.data());
  long wraps = 0;
  for (int i = 0; i < s.size(); ++i)
    for (int d = 0; d < 2; ++d) {
      wraps += std::abs(image[2 * i + d]);
      const double unwrapped = s.xyz[3 * i + d] + image[2 * i + d] * 6.0;
      // The unwrapped motion is continuous: far less than one period on average (100 sweeps
      // of steps <= 0.3 in a settling bed), where a lost wrap would show as ~6.
      EXPECT_LT(std::fabs(unwrapped - before[3 * i + d]), 3.0);
    }
  EXPECT_GT(wraps, 0);
}

// find_violation against the brute-force oracle on random configurations, with and without
// overlaps, periodic and walled.
TEST(Settle, FindViolationAgreesWithBruteForce)
{
  int with = 0, without = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const bool periodic = seed % 2;
    const CounterRandom rng(seed, 99);
    Scene s;
    const double side = 6.0;
    s.box = make_box(side, periodic);
    const int n = 20 + static_cast<int>(seed % 7) * 5;
    // Random points; radii small enough that roughly half the scenes have an overlap.
    const double r_scale = 0.15 + 0.01 * (seed % 10);
    for (int i = 0; i < n; ++i) {
      const RandomBlock w = rng.block(i);
      const double r = r_scale * (0.6 + 0.4 * uniform_from_u32(w[3]));
      s.radius.push_back(r);
      const double lo = periodic ? 0.0 : r, span = periodic ? side : side - 2 * r;
      s.xyz.push_back(lo + span * uniform_from_u32(w[0]));
      s.xyz.push_back(lo + span * uniform_from_u32(w[1]));
      s.xyz.push_back(r + 2.5 * uniform_from_u32(w[2]));
    }
    const OracleReport rep = brute_force_check(s.xyz.data(), s.radius.data(), n, s.box, kTol);
    const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), n, s.box, kTol);
    const bool oracle_bad = rep.pair_overlaps + rep.plane_violations > 0;
    EXPECT_EQ(v.i != -1, oracle_bad) << "seed " << seed;
    (oracle_bad ? with : without)++;
    if (v.i >= 0 && v.j >= 0) {
      // The reported pair really overlaps (minimum image) and the gap is its overlap depth.
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        double dd = s.xyz[3 * v.j + d] - s.xyz[3 * v.i + d];
        if (d < 2 && periodic) dd -= side * std::round(dd / side);
        d2 += dd * dd;
      }
      EXPECT_NEAR(v.gap, std::sqrt(d2) - s.radius[v.i] - s.radius[v.j], 1e-12);
      EXPECT_LT(v.gap, 0.0);
    }
  }
  EXPECT_GT(with, 10);
  EXPECT_GT(without, 10);
}

// The only overlap of the scene is across the periodic corner (x and y at once).
TEST(Settle, FindViolationAcrossThePeriodicCorner)
{
  Scene s;
  s.box = make_box(10.0, true);
  s.radius = {1.0, 1.0, 1.0};
  s.xyz = {0.3, 0.4, 1.0, 9.2, 9.3, 1.2, 5.0, 5.0, 1.0};
  const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), 3, s.box, kTol);
  ASSERT_NE(v.i, -1);
  EXPECT_EQ(std::min(v.i, v.j), 0);
  EXPECT_EQ(std::max(v.i, v.j), 1);
  EXPECT_NEAR(v.gap, std::sqrt(1.1 * 1.1 + 1.1 * 1.1 + 0.2 * 0.2) - 2.0, 1e-12);
  s.box.periodic[0] = s.box.periodic[1] = false;  // without images they are far apart
  EXPECT_EQ(Settler::find_violation(s.xyz.data(), s.radius.data(), 3, s.box, kTol).i, -1);
}

TEST(Settle, BadParametersThrowNamingTheParameter)
{
  Scene s = dilute_lattice(20, 6.0, 0.5, true, false, 1);
  Settler settler;
  auto expect_throw = [&](SettleParams p, const char *name) {
    try {
      settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box, p);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument &e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  const SettleParams good = paper_params(0.5, 1, 1);
  SettleParams p = good;
  p.d_max = 0;
  expect_throw(p, "dmax");
  p = good;
  p.d_max = 7.0;  // longer than the periodic box
  expect_throw(p, "dmax");
  p = good;
  p.theta0 = 1001.0;  // above defaults::kThetaWidthMax (theta0 may exceed pi/2)
  expect_throw(p, "theta0");
  p = good;
  p.theta0 = 0.0;
  expect_throw(p, "theta0");
  p = good;
  p.eta = 0.0;
  expect_throw(p, "eta");
  p = good;
  p.eta = 1.0;  // a relative change of <Z>: 1 would stop at the first check
  expect_throw(p, "eta");
  p = good;
  p.max_checks = 0;
  expect_throw(p, "max_checks");
  p = good;
  p.check_interval = -1;
  expect_throw(p, "check");
  p = good;
  p.contact_tol = -1e-3;
  expect_throw(p, "contact_tol");
  s.radius[3] = -1.0;
  expect_throw(good, "radius[3]");
  s.radius[3] = 0.5;
  s.box.hi[0] = 0.5;  // periodic length below one diameter
  expect_throw(good, "periodic box length x");
}

// The sweep cap in checks: ceil(max_sweeps * movable / trials per check), the product saturated;
// a check interval beyond the cap is refused.
TEST(Settle, SweepCapInChecks)
{
  EXPECT_EQ(Settler::trials_per_check(0, 37), 37);
  EXPECT_EQ(Settler::trials_per_check(5, 37), 5);
  EXPECT_EQ(Settler::max_checks_for_sweeps(10, 0, 37), 10);   // one check per sweep
  EXPECT_EQ(Settler::max_checks_for_sweeps(10, 5, 37), 74);   // ceil(370 / 5)
  EXPECT_EQ(Settler::max_checks_for_sweeps(1, 37, 37), 1);    // one check, the whole cap
  // a check beyond the cap (its first check would run past it; 9e18 trials never end)
  EXPECT_THROW(Settler::max_checks_for_sweeps(1, 1000, 37), std::invalid_argument);
  EXPECT_THROW(Settler::max_checks_for_sweeps(10, std::numeric_limits<long>::max(), 200),
               std::invalid_argument);
  // a cap beyond a long's trials saturates instead of wrapping to a few sweeps
  const long huge = 50000000000000000L;
  EXPECT_EQ(Settler::max_checks_for_sweeps(huge, 0, 200),
            std::numeric_limits<long>::max() / 200 + 1);
  EXPECT_EQ(Settler::max_checks_for_sweeps(huge, 0, 1), huge);
  EXPECT_THROW(Settler::max_checks_for_sweeps(0, 0, 37), std::invalid_argument);
  EXPECT_THROW(Settler::max_checks_for_sweeps(1, -1, 37), std::invalid_argument);
  // 'stop drift' never stops before its window: a window beyond the cap's checks is refused
  // (every redeposition would reach the cap); the window at the cap is allowed
  SettleParams drift;
  drift.stop = StopRule::Drift;
  drift.max_checks = 30;
  drift.drift_window = 31;
  EXPECT_THROW(Settler::make_convergence_check(drift, 37, 1.0), std::invalid_argument);
  drift.drift_window = 30;
  EXPECT_NO_THROW(Settler::make_convergence_check(drift, 37, 1.0));
  drift.stop = StopRule::Change;
  drift.drift_window = 31;  // unused by 'stop change'
  EXPECT_NO_THROW(Settler::make_convergence_check(drift, 37, 1.0));
}

// In a cylinder: a redeposition after a tap leaves every sphere inside the wall (all-pairs
// check), and a sphere pushed across the wall is found as a violation of kCylinderWall with
// its radial gap.
TEST(Settle, CylinderRedepositionAndViolation)
{
  Scene s = in_cylinder(random_loose(400, 8.0, 0.5, false, true, 21, 0.3), 4.0);
  Settler settler;
  const SettleResult res = settler.settle(s.xyz.data(), s.radius.data(), nullptr, s.size(), s.box,
                                          paper_params(0.5, 5, 1, 1e-6, 2000));
  EXPECT_LT(res.mean_height, res.mean_height_start);
  expect_valid(s, "cylinder poly");
  // push sphere 0 radially 1e-3 beyond its reach
  const double dx = s.xyz[0] - s.box.cylinder_cx, dy = s.xyz[1] - s.box.cylinder_cy;
  const double d = std::sqrt(dx * dx + dy * dy), reach = s.box.cylinder_radius - s.radius[0];
  const double out = (reach + 1e-3) / std::max(d, 1e-9);
  s.xyz[0] = s.box.cylinder_cx + (d > 1e-9 ? dx * out : reach + 1e-3);
  s.xyz[1] = s.box.cylinder_cy + (d > 1e-9 ? dy * out : 0.0);
  const Violation v = Settler::find_violation(s.xyz.data(), s.radius.data(), s.size(), s.box, kTol);
  if (v.j == kCylinderWall) {
    EXPECT_EQ(v.i, 0);
    EXPECT_NEAR(v.gap, -1e-3, 1e-9);
  } else {
    EXPECT_GE(v.j, 0) << "sphere 0 pushed out must be reported (a sphere or the wall)";
  }
}
