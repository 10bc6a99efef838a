// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the windowed trial executor (threads inside one rank, tapmc_sphere_mover.cpp): its
// conflict rule against an all-pairs oracle of the pairs that can interact within a window, and
// the serial trajectory bit for bit (positions, image shifts, trials, accepted moves, checks,
// <Z>, moved spheres in order) with 2, 3, 4 and 8 threads (8: more threads than cores) on
// periodic and walled boxes, mono- and polydisperse spheres, with obstacles, a move region and
// sweep order, over several seeds.
#include "settle_test_scenes.h"
#include "tapmc_defaults.h"
#include "tapmc_settle.h"
#include "tapmc_sphere_mover.h"
#include "tapmc_thread_team.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;

namespace {

constexpr double kTol = defaults::kContactTolerance;
const int kThreadCounts[] = {2, 3, 4, 8};

// Nearest-image distance between points a and b of the scene's box.
double distance(const SettleBox &box, const double *a, const double *b)
{
  double sq = 0.0;
  for (int d = 0; d < 3; ++d) {
    double delta = a[d] - b[d];
    if (d < 2 && box.periodic[d]) {
      const double length = box.hi[d] - box.lo[d];
      delta -= length * std::round(delta / length);
    }
    sq += delta * delta;
  }
  return std::sqrt(sq);
}

// Every pair whose trials can interact within one window (each sphere moves at most
// kThreadWindowPicks times by at most d_max, so a trial's new centre and the other sphere are
// then within R_i + R_j only if they start within R_i + R_j + 2 kThreadWindowPicks d_max) must
// be ordered by the executor. Returns the pairs that are not ordered (the rule must not be
// "everything in order", or threads would never run at once).
long expect_conflicts_ordered(const SphereMover &mover, const Scene &s, double d_max,
                              const std::string &what)
{
  const double window_travel = 2.0 * defaults::kThreadWindowPicks * d_max;
  long unordered = 0, missed = 0;
  for (int i = 0; i < s.size(); ++i)
    for (int j = i + 1; j < s.size(); ++j) {
      const bool ordered = mover.window_orders(i, j);
      EXPECT_EQ(ordered, mover.window_orders(j, i)) << what;
      unordered += !ordered;
      const double reach = s.radius[i] + s.radius[j] + window_travel;
      if (!ordered && distance(s.box, mover.position(i), mover.position(j)) < reach) ++missed;
    }
  EXPECT_EQ(missed, 0) << what << ": pairs that can interact in a window but run unordered";
  return unordered;
}

struct Trajectory {
  std::vector<double> xyz;
  std::vector<int> image;
  SettleResult result;
};

Trajectory settle_with(const Scene &start, const unsigned char *movable, const SettleParams &p,
                       int threads, SphereMover::WindowStats *stats = nullptr)
{
  Trajectory out;
  out.xyz = start.xyz;
  out.image.assign(2 * start.radius.size(), 0);
  Settler settler;
  settler.set_threads(threads);
  out.result = settler.settle(out.xyz.data(), start.radius.data(), movable, start.size(),
                              start.box, p, out.image.data());
  if (stats) *stats = settler.mover().window_stats();
  return out;
}

void expect_same_trajectory(const Trajectory &serial, const Trajectory &threaded,
                            const std::string &what)
{
  EXPECT_EQ(std::memcmp(serial.xyz.data(), threaded.xyz.data(),
                        serial.xyz.size() * sizeof(double)), 0)
      << what << ": positions differ";
  EXPECT_EQ(serial.image, threaded.image) << what;
  EXPECT_EQ(serial.result.trials, threaded.result.trials) << what;
  EXPECT_EQ(serial.result.accepted, threaded.result.accepted) << what;
  EXPECT_EQ(serial.result.checks, threaded.result.checks) << what;
  EXPECT_EQ(serial.result.hit_cap, threaded.result.hit_cap) << what;
  EXPECT_EQ(std::memcmp(&serial.result.mean_height, &threaded.result.mean_height, sizeof(double)),
            0)
      << what << ": <Z> " << serial.result.mean_height << " vs " << threaded.result.mean_height;
}

// Blocks long enough for the windowed executor at every thread count tested.
SettleParams windowed_params(double r, std::uint64_t seed, std::uint64_t stream, double eta,
                             long max_checks)
{
  SettleParams p = paper_params(r, seed, stream, eta, max_checks);
  p.check_interval = 8192;
  return p;
}

}  // namespace

TEST(ThreadTeam, RunsEveryMemberOnceAndPublishesTheirWrites)
{
  for (int size : {1, 2, 5}) {
    ThreadTeam team(size);
    std::vector<long> written(static_cast<std::size_t>(size), 0);
    for (int job = 0; job < 200; ++job) {
      auto add = [&](int member) { written[member] += member + 1; };
      team.run(add);
      if (job == 100) team.sleep();  // a sleeping team wakes for the next job
    }
    for (int m = 0; m < size; ++m) EXPECT_EQ(written[m], 200L * (m + 1)) << "size " << size;
  }
}

TEST(ThreadedMover, ThreadsOutsideTheirRangeAreRefused)
{
  SphereMover mover;
  Settler settler;
  for (int bad : {0, -1, defaults::kMaxThreads + 1}) {
    EXPECT_THROW(mover.set_threads(bad), std::invalid_argument) << bad;
    EXPECT_THROW(settler.set_threads(bad), std::invalid_argument) << bad;
  }
  try {
    mover.set_threads(0);
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("threads = 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[1, 64]"), std::string::npos) << e.what();
  }
}

// The conflict rule against the all-pairs oracle, at the start and after windows that moved
// spheres across cells and updated lists (a loose start falls: many updates).
TEST(ThreadedMover, ConflictRuleOrdersEveryPairThatCanInteract)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (int poly = 0; poly < 2; ++poly)
      for (std::uint64_t seed = 1; seed <= 2; ++seed)
        for (int threads : {2, 4}) {
          const std::string what =
              variant_name(periodic, poly, seed) + ", " + std::to_string(threads) + " threads";
          const Scene s = random_loose(500, 10.0, 0.5, periodic, poly, seed, 0.3);
          const double d_max = 0.1;
          SphereMover mover;
          mover.set_threads(threads);
          mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
          long unordered = expect_conflicts_ordered(mover, s, d_max, what + ", start");
          const std::vector<int> candidates = [&] {
            std::vector<int> all(s.size());
            for (int i = 0; i < s.size(); ++i) all[i] = i;
            return all;
          }();
          const TrialMoveSampler sampler(d_max, defaults::kThetaWidth);
          const CounterRandom rng(seed, 11);
          TrialTally tally;
          long cursor = 0;
          for (int block = 0; block < 4; ++block)
            mover.run(candidates.data(), s.size(), PickOrder::Random, cursor, sampler, rng,
                      static_cast<std::uint64_t>(block) * 20000, 20000, nullptr, tally);
          EXPECT_GT(mover.window_stats().windows, 0) << what;
          EXPECT_GT(mover.local_updates(), 100) << what;
          EXPECT_EQ(mover.check_lists(), "") << what;
          unordered += expect_conflicts_ordered(mover, s, d_max, what + ", after 80000 trials");
          EXPECT_GT(unordered, 0) << what;
        }
}

// A tap of a settled bed (the redeposition workload) and the fall of a loose start (many list
// updates and cell changes between windows), stopped by the <Z> rule: the serial trajectory.
TEST(ThreadedMover, SettleGivesTheSerialTrajectoryBitForBit)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (int poly = 0; poly < 2; ++poly)
      for (std::uint64_t seed = 1; seed <= 2; ++seed) {
        const std::string scene = variant_name(periodic, poly, seed);
        Scene bed = settled_bed(900, 12.0, 0.5, periodic, poly, seed, 100);
        dilate(bed, 0.02);
        const Scene loose = random_loose(600, 10.0, 0.5, periodic, poly, seed + 10, 0.25);
        const Scene *starts[2] = {&bed, &loose};
        const char *names[2] = {"tapped bed", "loose start"};
        for (int k = 0; k < 2; ++k) {
          const SettleParams p = windowed_params(0.5, seed, 40 + k, 1e-4, 8);
          const Trajectory serial = settle_with(*starts[k], nullptr, p, 1);
          EXPECT_GT(serial.result.accepted, 1000) << scene;
          for (int threads : kThreadCounts) {
            SphereMover::WindowStats stats;
            const std::string what =
                scene + ", " + names[k] + ", " + std::to_string(threads) + " threads";
            expect_same_trajectory(serial, settle_with(*starts[k], nullptr, p, threads, &stats),
                                   what);
            EXPECT_EQ(stats.trials, serial.result.trials) << what << ": not all windowed";
          }
        }
      }
}

// Fixed obstacles among the moving spheres, and the default check interval (one sweep) on a
// bed big enough for windows: still the serial trajectory.
TEST(ThreadedMover, SettleWithObstaclesGivesTheSerialTrajectory)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const std::string scene = variant_name(periodic, seed == 2, seed) + ", obstacles";
      Scene bed = settled_bed(2400, 16.0, 0.5, periodic, seed == 2, seed, 60);
      dilate(bed, 0.02);
      std::vector<unsigned char> movable(bed.radius.size(), 1);
      for (std::size_t i = 0; i < movable.size(); i += 5) movable[i] = 0;
      SettleParams p = paper_params(0.5, seed, 77, 1e-4, 6);
      const Trajectory serial = settle_with(bed, movable.data(), p, 1);
      for (int threads : {2, 3}) {
        SphereMover::WindowStats stats;
        const std::string what = scene + ", " + std::to_string(threads) + " threads";
        expect_same_trajectory(serial, settle_with(bed, movable.data(), p, threads, &stats), what);
        EXPECT_GT(stats.windows, 0) << what;
      }
    }
}

// The engine as the decomposed scheme drives it: a move region, a subset of candidates, sweep
// and random order, obstacles moved between blocks, short blocks (the serial loop) between long
// ones (windows). Tallies bit for bit, moved spheres in the same order, same positions.
TEST(ThreadedMover, RunMatchesOneThreadWithRegionSweepAndObstacles)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const bool poly = seed != 2;
      Scene s = settled_bed(800, 11.0, 0.5, periodic, poly, seed, 60);
      dilate(s, 0.03);
      std::vector<int> candidates, obstacles;
      for (int i = 0; i < s.size(); ++i) (i % 4 ? candidates : obstacles).push_back(i);
      const long m = static_cast<long>(candidates.size());
      const MoveRegion region{{0.5, 0.3, 0.0}, {10.2, 10.6, 40.0}};
      const double d_max = 0.1;
      const TrialMoveSampler sampler(d_max, defaults::kThetaWidth);
      const CounterRandom rng(seed, 21);
      for (int threads : kThreadCounts) {
        const std::string what =
            variant_name(periodic, poly, seed) + ", " + std::to_string(threads) + " threads";
        SphereMover one, many;
        many.set_threads(threads);
        one.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
        many.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
        TrialTally tally_one, tally_many;
        long cursor_one = 0, cursor_many = 0;
        std::uint64_t first = 0;
        std::vector<SphereMover::Moved> moved_one, moved_many;
        for (int block = 0; block < 12; ++block) {
          const PickOrder order = block % 3 == 1 ? PickOrder::Sweep : PickOrder::Random;
          const long trials = block % 4 == 3 ? 37 : 9000;
          const MoveRegion *r = block % 2 ? &region : nullptr;
          one.run(candidates.data(), m, order, cursor_one, sampler, rng, first, trials, r,
                  tally_one);
          many.run(candidates.data(), m, order, cursor_many, sampler, rng, first, trials, r,
                   tally_many);
          first += static_cast<std::uint64_t>(trials);
          EXPECT_EQ(cursor_one, cursor_many) << what << " block " << block;
          one.take_moved(moved_one);
          many.take_moved(moved_many);
          ASSERT_EQ(moved_one.size(), moved_many.size()) << what << " block " << block;
          for (std::size_t k = 0; k < moved_one.size(); ++k) {
            EXPECT_EQ(moved_one[k].index, moved_many[k].index) << what;
            EXPECT_EQ(std::memcmp(moved_one[k].x, moved_many[k].x, sizeof(moved_one[k].x)), 0)
                << what;
            EXPECT_EQ(moved_one[k].image[0], moved_many[k].image[0]) << what;
            EXPECT_EQ(moved_one[k].image[1], moved_many[k].image[1]) << what;
          }
          // An obstacle (a ghost, for the decomposed scheme) moved a little upwards: free.
          const int o = obstacles[static_cast<std::size_t>(block) % obstacles.size()];
          double p[3] = {one.position(o)[0], one.position(o)[1], one.position(o)[2] + 3.0};
          one.set_position(o, p);
          many.set_position(o, p);
        }
        EXPECT_EQ(tally_one.trials, tally_many.trials) << what;
        EXPECT_EQ(tally_one.accepted, tally_many.accepted) << what;
        EXPECT_EQ(std::memcmp(&tally_one.sum_dz, &tally_many.sum_dz, sizeof(double)), 0) << what;
        EXPECT_GT(tally_one.accepted, 500) << what;
        for (int i = 0; i < s.size(); ++i) {
          EXPECT_EQ(std::memcmp(one.position(i), many.position(i), 3 * sizeof(double)), 0)
              << what << " sphere " << i;
          EXPECT_EQ(one.image_shift(i, 0), many.image_shift(i, 0)) << what;
          EXPECT_EQ(one.image_shift(i, 1), many.image_shift(i, 1)) << what;
        }
        EXPECT_EQ(many.check_lists(), "") << what;
        EXPECT_GT(many.window_stats().windows, 0) << what;
      }
    }
}
