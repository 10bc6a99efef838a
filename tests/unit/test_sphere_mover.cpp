// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the trial-move engine (SphereMover): every decision against an all-pairs mover making
// the same draws, with periodic sides and walls, mono- and polydisperse spheres, a move region,
// obstacles moved between blocks (small steps and large jumps), and free fall from loose starts
// (many local list updates).
#include "settle_test_scenes.h"
#include "tapmc_contact.h"
#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
#include "tapmc_memory.h"
#include "tapmc_sphere_mover.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_scenes;

namespace {

constexpr double kTol = defaults::kContactTolerance;

// The reference: the same trial arithmetic (wrap, region, planes, nearest-image overlap test of
// tapmc_contact.h) against every other sphere, no lists.
class AllPairsMover {
 public:
  AllPairsMover(const Scene &s, double d_max) : box_(s.box), radius_(s.radius), d_max_(d_max)
  {
    xyz_.resize(s.xyz.size());
    image_.assign(2 * s.radius.size(), 0);
    for (int i = 0; i < s.size(); ++i) set_position(i, &s.xyz[3 * i]);
  }

  void set_position(int i, const double *p)
  {
    for (int d = 0; d < 3; ++d) xyz_[3 * i + d] = p[d];
    for (int d = 0; d < 2; ++d)
      if (box_.periodic[d]) {  // the kernel's wrap (tapmc_math.h), images counted from 0
        image_[2 * i + d] = 0;
        xyz_[3 * i + d] = wrap_periodic(p[d], box_.lo[d], box_.hi[d], box_.hi[d] - box_.lo[d],
                                        image_[2 * i + d]);
      }
  }

  // Trial of sphere i by `move`: true when accepted (and then made).
  bool trial(int i, const Displacement &move, const MoveRegion *region)
  {
    const double r = radius_[i];
    double p[3] = {xyz_[3 * i] + move.dx, xyz_[3 * i + 1] + move.dy, xyz_[3 * i + 2] + move.dz};
    int wrap[2] = {0, 0};
    for (int d = 0; d < 2; ++d)
      if (box_.periodic[d]) {
        const double lo = box_.lo[d], hi = box_.hi[d], length = hi - lo;
        if (p[d] < lo) {
          p[d] += length;
          wrap[d] = -1;
          if (p[d] >= hi) p[d] = lo;
        } else if (p[d] >= hi) {
          p[d] -= length;
          wrap[d] = 1;
          if (p[d] < lo) p[d] = lo;
        }
      }
    if (region)
      for (int d = 0; d < 3; ++d)
        if (!(p[d] >= region->lo[d] && p[d] < region->hi[d])) return false;
    if (gap_violates(floor_gap(p[2], r, box_.floor_z), r, kTol)) return false;
    for (int d = 0; d < 2; ++d) {
      if (box_.wall_lo[d] && gap_violates(low_wall_gap(p[d], r, box_.wall_lo_pos[d]), r, kTol))
        return false;
      if (box_.wall_hi[d] && gap_violates(high_wall_gap(p[d], r, box_.wall_hi_pos[d]), r, kTol))
        return false;
    }
    if (box_.cylinder) {  // the wall test of tapmc_cylinder.h (the kernel's arithmetic)
      const CylinderWall wall{box_.cylinder_cx, box_.cylinder_cy, box_.cylinder_radius, kTol};
      if (!wall.contains_sphere(p[0], p[1], r)) return false;
    }
    for (int j = 0; j < static_cast<int>(radius_.size()); ++j) {
      if (j == i) continue;
      double sep[2];
      for (int d = 0; d < 2; ++d) {
        const double raw = xyz_[3 * j + d] - p[d];
        double shift = 0.0;
        if (box_.periodic[d]) {
          const double length = box_.hi[d] - box_.lo[d], half = 0.5 * length;
          shift = raw > half ? -length : (raw < -half ? length : 0.0);
        }
        sep[d] = separation(xyz_[3 * j + d], p[d], shift);
      }
      const double d2 = distance_sq(sep[0], sep[1], xyz_[3 * j + 2] - p[2]);
      if (d2 < overlap_threshold_sq(r, radius_[j], 1.0 - kTol)) return false;
    }
    for (int d = 0; d < 3; ++d) xyz_[3 * i + d] = p[d];
    image_[2 * i] += wrap[0];
    image_[2 * i + 1] += wrap[1];
    return true;
  }

  const double *position(int i) const { return &xyz_[3 * i]; }
  int image(int i, int d) const { return image_[2 * i + d]; }
  double d_max() const { return d_max_; }

 private:
  SettleBox box_;
  std::vector<double> xyz_, radius_;
  std::vector<int> image_;
  double d_max_;
};

// Runs trials first .. first + count - 1 through the oracle (same draws as SphereMover::run).
long oracle_block(AllPairsMover &oracle, const std::vector<int> &candidates, PickOrder order,
                  long &cursor, const TrialMoveSampler &sampler, const CounterRandom &rng,
                  std::uint64_t first, long count, const MoveRegion *region)
{
  const long m = static_cast<long>(candidates.size());
  const std::uint32_t n_pick = order == PickOrder::Random ? static_cast<std::uint32_t>(m) : 0u;
  long accepted = 0;
  for (long t = 0; t < count; ++t) {
    const TrialDraw draw = sampler.draw(rng, first + static_cast<std::uint64_t>(t), n_pick);
    long k = draw.pick;
    if (order == PickOrder::Sweep) {
      k = cursor;
      if (++cursor == m) cursor = 0;
    }
    accepted += oracle.trial(candidates[k], draw.move, region);
  }
  return accepted;
}

// Positions and image counts of the mover and the oracle agree bit for bit; the packing has no
// overlap (all pairs, all images) and no plane violation.
void expect_same_state(const SphereMover &mover, const AllPairsMover &oracle, const Scene &s,
                       const std::string &what)
{
  Scene now = s;
  int differ = 0;
  for (int i = 0; i < s.size(); ++i) {
    for (int d = 0; d < 3; ++d) {
      differ += mover.position(i)[d] != oracle.position(i)[d];
      now.xyz[3 * i + d] = mover.position(i)[d];
    }
    for (int d = 0; d < 2; ++d) differ += mover.image_shift(i, d) != oracle.image(i, d);
  }
  EXPECT_EQ(differ, 0) << what;
  const OracleReport rep = brute_force_check(now.xyz.data(), now.radius.data(), now.size(), now.box, kTol);
  EXPECT_EQ(rep.pair_overlaps, 0) << what << " worst gap " << rep.worst_gap;
  EXPECT_EQ(rep.plane_violations, 0) << what << " worst gap " << rep.worst_gap;
}

struct Block {
  long trials;
  PickOrder order;
};

// Runs blocks of trials through the mover and the oracle and compares after each block.
// Blocks of one trial compare every single decision.
long run_against_oracle(const Scene &s, const std::vector<int> &candidates, double d_max,
                        const std::vector<Block> &blocks, const MoveRegion *region,
                        std::uint64_t seed, const std::string &what, SphereMover &mover,
                        double theta0 = defaults::kThetaWidth)
{
  mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
  AllPairsMover oracle(s, d_max);
  const TrialMoveSampler sampler(d_max, theta0);
  const CounterRandom rng(seed, 17);
  TrialTally tally;
  long cursor_mover = 0, cursor_oracle = 0, accepted_oracle = 0;
  std::uint64_t first = 0;
  const long m = static_cast<long>(candidates.size());
  for (const Block &b : blocks) {
    const long before = tally.accepted;
    mover.run(candidates.data(), m, b.order, cursor_mover, sampler, rng, first, b.trials, region,
              tally);
    const long oracle_accepted = oracle_block(oracle, candidates, b.order, cursor_oracle, sampler,
                                              rng, first, b.trials, region);
    accepted_oracle += oracle_accepted;
    EXPECT_EQ(tally.accepted - before, oracle_accepted) << what << " block at trial " << first;
    EXPECT_EQ(cursor_mover, cursor_oracle) << what;
    first += static_cast<std::uint64_t>(b.trials);
  }
  EXPECT_EQ(mover.check_lists(), "") << what;
  EXPECT_EQ(tally.trials, static_cast<long>(first)) << what;
  EXPECT_EQ(tally.accepted, accepted_oracle) << what;
  expect_same_state(mover, oracle, s, what);
  return tally.accepted;
}

// Can sphere o of s sit at p (inside the box, no overlap with any other sphere, all images)?
bool free_place(const Scene &s, int o, const double *p)
{
  const double r = s.radius[o];
  if (p[2] - r < s.box.floor_z) return false;
  for (int d = 0; d < 2; ++d)
    if (!s.box.periodic[d] && (p[d] - r < s.box.lo[d] || p[d] + r > s.box.hi[d])) return false;
  for (int j = 0; j < s.size(); ++j) {
    if (j == o) continue;
    for (int ix = -1; ix <= 1; ++ix)
      for (int iy = -1; iy <= 1; ++iy) {
        if ((ix && !s.box.periodic[0]) || (iy && !s.box.periodic[1])) continue;
        const double dx = s.xyz[3 * j] + ix * (s.box.hi[0] - s.box.lo[0]) - p[0];
        const double dy = s.xyz[3 * j + 1] + iy * (s.box.hi[1] - s.box.lo[1]) - p[1];
        const double dz = s.xyz[3 * j + 2] - p[2];
        const double reach = r + s.radius[j];
        if (dx * dx + dy * dy + dz * dz < reach * reach) return false;
      }
  }
  return true;
}

std::vector<int> all_of(int n)
{
  std::vector<int> ids(n);
  for (int i = 0; i < n; ++i) ids[i] = i;
  return ids;
}

}  // namespace

// Free fall from a loose random start (many local updates) and settling: periodic and walls,
// mono and poly, Random and Sweep order, blocks of one trial (every decision compared) and of
// many trials; the accepted moves, final positions and image counts are the oracle's.
TEST(SphereMover, MatchesAllPairsOracleFromLooseStarts)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (int poly = 0; poly < 2; ++poly)
      for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const std::string what = variant_name(periodic, poly, seed);
        const Scene s = random_loose(160, 6.0, 0.5, periodic, poly, seed, 0.25);
        std::vector<Block> blocks;
        for (int k = 0; k < 300; ++k) blocks.push_back({1, PickOrder::Random});
        for (int k = 0; k < 30; ++k) blocks.push_back({160, k % 3 ? PickOrder::Random : PickOrder::Sweep});
        blocks.push_back({40 * 160 + 7, PickOrder::Random});
        SphereMover mover;
        const long accepted = run_against_oracle(s, all_of(s.size()), 0.1, blocks, nullptr, seed, what, mover);
        EXPECT_GT(accepted, 1000) << what;
        EXPECT_GT(mover.local_updates(), 100) << what;
        EXPECT_EQ(mover.full_builds(), 1) << what;
      }
}

// Dense settled beds (short lists, few updates), a box narrower than the list reach (one cell
// across: the cell query must not list a sphere twice), a wide theta (many periodic wraps).
TEST(SphereMover, MatchesAllPairsOracleOnBedsAndNarrowBoxes)
{
  struct Case {
    Scene start;
    double d_max;
    const char *name;
  };
  Scene bed = settled_bed(300, 6.0, 0.5, true, true, 5, 100);
  dilate(bed, 0.02);
  Scene walls_bed = settled_bed(300, 6.0, 0.5, false, false, 6, 100);
  dilate(walls_bed, 0.02);
  const std::vector<Case> cases = {{bed, 0.1, "pbc poly bed"},
                                   {walls_bed, 0.1, "walls mono bed"},
                                   {dilute_lattice(30, 2.4, 1.0, true, true, 93), 0.2, "narrow pbc"},
                                   {dilute_lattice(40, 8.0, 1.0, true, false, 94), 1.5, "2-cell pbc, big steps"}};
  for (const Case &c : cases) {
    std::vector<Block> blocks;
    for (int k = 0; k < 200; ++k) blocks.push_back({1, PickOrder::Random});
    blocks.push_back({100 * c.start.size(), PickOrder::Random});
    blocks.push_back({50 * c.start.size(), PickOrder::Sweep});
    for (double skin : {0.01, 0.2, 2.0}) {
      SphereMover mover;
      mover.set_skin(skin);
      EXPECT_GT(run_against_oracle(c.start, all_of(c.start.size()), c.d_max, blocks, nullptr, 3,
                                   std::string(c.name) + " skin " + std::to_string(skin), mover),
                0)
          << c.name;
    }
  }
}

// A cylindrical container: from loose starts (mono and poly, many moves reach the wall) and at
// extreme settings (theta0 = pi/2, steps of half a radius), every decision and the final state
// are the all-pairs oracle's, and no centre leaves the wall's reach.
TEST(SphereMover, MatchesAllPairsOracleInACylinder)
{
  for (int poly = 0; poly < 2; ++poly)
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Scene s = in_cylinder(random_loose(260, 8.0, 0.5, false, poly, seed, 0.25), 4.0);
      const std::string what = std::string("cylinder ") + (poly ? "poly" : "mono") + " seed " +
                               std::to_string(seed);
      ASSERT_GT(s.size(), 150) << what;
      std::vector<Block> blocks;
      for (int k = 0; k < 300; ++k) blocks.push_back({1, PickOrder::Random});
      blocks.push_back({40 * s.size(), PickOrder::Random});
      blocks.push_back({5 * s.size(), PickOrder::Sweep});
      for (double theta0 : {defaults::kThetaWidth, 0.5 * kPi}) {
        SphereMover mover;
        EXPECT_GT(run_against_oracle(s, all_of(s.size()), theta0 > 1 ? 0.25 : 0.1, blocks, nullptr,
                                     seed, what, mover, theta0),
                  1000)
            << what;
      }
    }
}

// A move region: no accepted centre ever leaves it; decisions as the oracle's; the spheres
// outside the region never move.
TEST(SphereMover, MoveRegionRejectsTrialsLeavingIt)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const std::string what = std::string(periodic ? "PBC" : "walls") + " seed " + std::to_string(seed);
      const Scene s = random_loose(200, 7.0, 0.5, periodic, seed % 2, seed, 0.25);
      const MoveRegion region{{1.0, 0.5, 0.6}, {5.5, 6.8, 4.0}};
      std::vector<Block> blocks;
      for (int k = 0; k < 200; ++k) blocks.push_back({1, PickOrder::Random});
      for (int k = 0; k < 20; ++k) blocks.push_back({200, PickOrder::Random});
      SphereMover mover;
      run_against_oracle(s, all_of(s.size()), 0.1, blocks, &region, seed, what, mover);
      for (int i = 0; i < s.size(); ++i) {
        const double *p = mover.position(i);
        bool inside = true;
        for (int d = 0; d < 3; ++d) inside = inside && p[d] >= region.lo[d] && p[d] < region.hi[d];
        bool moved = false;
        for (int d = 0; d < 3; ++d) moved = moved || p[d] != s.xyz[3 * i + d];
        if (moved) EXPECT_TRUE(inside) << what << " sphere " << i;
      }
    }
}

// Obstacles (never picked) moved by set_position between blocks, by small steps and by large
// jumps (anywhere in the box, and given outside the periodic box like a LAMMPS ghost): the lists
// follow, every decision is the oracle's.
TEST(SphereMover, ObstaclesMovedBetweenBlocks)
{
  for (int periodic = 0; periodic < 2; ++periodic)
    for (int poly = 0; poly < 2; ++poly)
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const std::string what = variant_name(periodic, poly, seed);
        Scene s = random_loose(180, 7.0, 0.5, periodic, poly, seed, 0.2);
        std::vector<int> candidates;
        std::vector<int> obstacles;
        for (int i = 0; i < s.size(); ++i) (i % 3 ? candidates : obstacles).push_back(i);
        const double d_max = 0.1;
        SphereMover mover;
        mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
        AllPairsMover oracle(s, d_max);
        const TrialMoveSampler sampler(d_max, defaults::kThetaWidth);
        const CounterRandom rng(seed, 5), jumps(seed, 6);
        TrialTally tally;
        long cursor = 0, cursor_oracle = 0;
        std::uint64_t first = 0, jump_word = 0;
        long jumps_made = 0;
        const long m = static_cast<long>(candidates.size());
        for (int block = 0; block < 40; ++block) {
          const long trials = block % 4 == 0 ? 1 : 150;
          const long before = tally.accepted;
          mover.run(candidates.data(), m, PickOrder::Random, cursor, sampler, rng, first, trials,
                    nullptr, tally);
          EXPECT_EQ(tally.accepted - before,
                    oracle_block(oracle, candidates, PickOrder::Random, cursor_oracle, sampler, rng,
                                 first, trials, nullptr))
              << what << " block " << block;
          first += static_cast<std::uint64_t>(trials);
          // Move a few obstacles to free places: small steps, or a jump anywhere.
          Scene now = s;
          for (int i = 0; i < s.size(); ++i)
            for (int d = 0; d < 3; ++d) now.xyz[3 * i + d] = oracle.position(i)[d];
          for (int moved = 0, tries = 0; moved < 6 && tries < 200; ++tries) {
            const int o = obstacles[jump_word % obstacles.size()];
            const RandomBlock w = jumps.block(jump_word++);
            const bool jump = tries % 2 == 1;
            double p[3];
            for (int d = 0; d < 3; ++d) {
              const double u = uniform_from_u32(w[d]);
              p[d] = jump ? (d < 2 ? 0.5 + 6.0 * u : 0.5 + 10.0 * u)
                          : now.xyz[3 * o + d] + 0.3 * (u - 0.5);
            }
            if (!free_place(now, o, p)) continue;
            if (periodic && jump) p[0] += 7.0 * (w[3] % 3 == 0 ? 1 : (w[3] % 3 == 1 ? -1 : 0));
            for (int d = 0; d < 3; ++d) now.xyz[3 * o + d] = p[d];
            mover.set_position(o, p);
            oracle.set_position(o, p);
            jumps_made += jump;
            ++moved;
          }
        }
        expect_same_state(mover, oracle, s, what);
        EXPECT_EQ(mover.check_lists(), "") << what;
        EXPECT_GT(tally.accepted, 100) << what;
        EXPECT_GT(jumps_made, 15) << what;
      }
}

// Bad arguments are refused with std::invalid_argument; an empty run does nothing.
TEST(SphereMover, ArgumentsAreChecked)
{
  const Scene s = dilute_lattice(50, 5.0, 0.5, true, false, 3);
  SphereMover mover;
  EXPECT_THROW(mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, 0.0, kTol),
               std::invalid_argument);
  EXPECT_THROW(mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, 6.0, kTol),
               std::invalid_argument);  // d_max beyond the periodic length
  EXPECT_THROW(mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, 0.1, 0.5),
               std::invalid_argument);  // contact tolerance
  EXPECT_THROW(mover.set_skin(0.0), std::invalid_argument);
  mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, 0.1, kTol);
  EXPECT_EQ(mover.full_builds(), 1);
  const double p[3] = {1, 1, 1};
  EXPECT_THROW(mover.set_position(s.size(), p), std::invalid_argument);
  const TrialMoveSampler sampler(0.1, defaults::kThetaWidth);
  const TrialMoveSampler too_far(0.2, defaults::kThetaWidth);
  const CounterRandom rng(1, 2);
  TrialTally tally;
  long cursor = 0;
  const std::vector<int> ids = all_of(s.size());
  EXPECT_THROW(mover.run(ids.data(), 0, PickOrder::Random, cursor, sampler, rng, 0, 10, nullptr, tally),
               std::invalid_argument);
  EXPECT_THROW(mover.run(ids.data(), s.size(), PickOrder::Random, cursor, too_far, rng, 0, 10,
                         nullptr, tally),
               std::invalid_argument);  // steps longer than the lists allow for
  mover.run(ids.data(), s.size(), PickOrder::Random, cursor, sampler, rng, 0, 0, nullptr, tally);
  EXPECT_EQ(tally.trials, 0);
  std::vector<int> bad_ids = ids;
  bad_ids[7] = s.size();
  EXPECT_THROW(mover.run(bad_ids.data(), s.size(), PickOrder::Random, cursor, sampler, rng, 0,
                         s.size(), nullptr, tally),
               std::invalid_argument);
  const double not_finite[3] = {1, std::nan(""), 1};
  EXPECT_THROW(mover.set_position(3, not_finite), std::invalid_argument);
}

// take_moved() lists exactly the spheres whose positions changed since the previous call, each
// once, with their positions and image shifts; obstacles placed with set_position are not among
// them. Periodic sides, so that moves wrap.
TEST(SphereMover, TakeMovedListsExactlyTheSpheresThatMoved)
{
  Scene s = random_loose(150, 7.0, 0.5, true, false, 9, 0.2);
  std::vector<int> candidates;
  for (int i = 0; i < s.size(); i += 2) candidates.push_back(i);
  const double d_max = 0.1;
  SphereMover mover;
  mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
  const TrialMoveSampler sampler(d_max, defaults::kThetaWidth);
  const CounterRandom rng(4, 2);
  TrialTally tally;
  long cursor = 0;
  std::vector<SphereMover::Moved> moved;
  std::uint64_t first = 0;
  bool wrapped = false;
  for (int block = 0; block < 6; ++block) {
    std::vector<double> before(3 * static_cast<std::size_t>(s.size()));
    for (int i = 0; i < s.size(); ++i)
      for (int d = 0; d < 3; ++d) before[3 * i + d] = mover.position(i)[d];
    const long trials = block == 3 ? 1 : 200;
    mover.run(candidates.data(), static_cast<long>(candidates.size()), PickOrder::Random, cursor,
              sampler, rng, first, trials, nullptr, tally);
    first += static_cast<std::uint64_t>(trials);
    const double *odd = mover.position(1);  // an obstacle moved from outside: not reported
    const double lifted[3] = {odd[0], odd[1], odd[2] + 5.0};
    mover.set_position(1, lifted);
    mover.take_moved(moved);
    std::vector<int> changed, listed;
    for (int i = 0; i < s.size(); ++i) {
      if (i == 1) continue;
      const double *p = mover.position(i);
      if (p[0] != before[3 * i] || p[1] != before[3 * i + 1] || p[2] != before[3 * i + 2])
        changed.push_back(i);
    }
    for (const SphereMover::Moved &m : moved) {
      listed.push_back(m.index);
      for (int d = 0; d < 3; ++d) EXPECT_EQ(m.x[d], mover.position(m.index)[d]);
      for (int d = 0; d < 2; ++d) {
        EXPECT_EQ(m.image[d], mover.image_shift(m.index, d));
        wrapped = wrapped || m.image[d] != 0;
      }
    }
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, changed) << "block " << block;
    if (block == 0) EXPECT_FALSE(moved.empty());
  }
  EXPECT_TRUE(wrapped);  // some move crossed a periodic side
  mover.take_moved(moved);
  EXPECT_TRUE(moved.empty());
}

// The kernel's large arrays: blocks of a large page or more start on a large-page boundary (so
// that the kernel can map them with huge pages), smaller ones come from the plain allocator;
// both hold and copy their elements as a std::vector does.
TEST(LargePageAllocator, LargeBlocksStartOnALargePageAndBehaveAsVectors)
{
  LargeVector<int> big(kLargePageBytes / sizeof(int) + 3, 7), small(100, 3);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kLargePageBytes, 0u);
  big[big.size() - 1] = 11;
  LargeVector<int> copy = big;
  EXPECT_EQ(copy.size(), big.size());
  EXPECT_EQ(copy.back(), 11);
  EXPECT_EQ(copy.front(), 7);
  copy.swap(small);
  EXPECT_EQ(copy.size(), 100u);
  EXPECT_EQ(small.back(), 11);
  small.resize(10);
  small.shrink_to_fit();
  EXPECT_EQ(small.size(), 10u);
}


// The stress case: a tight tube of 4 diameters, theta0 = pi/2 (moves down to
// horizontal) and steps up to a radius, 10^7 trials in blocks with a tap between blocks (the
// heights dilated 20 %, so that moves keep being accepted): after every block the independent
// all-pairs check (square roots, no lists) finds no overlap and no centre beyond the wall.
TEST(SphereMover, TightTubeTenMillionTrialsNeverCrossTheWall)
{
  Scene s = in_cylinder(random_loose(120, 4.0, 0.5, false, false, 11, 0.25), 2.0);
  ASSERT_GT(s.size(), 60);
  const double d_max = 0.5;
  const TrialMoveSampler sampler(d_max, 0.5 * kPi);
  const std::vector<int> ids = all_of(s.size());
  long cursor = 0, accepted = 0, at_wall = 0;
  for (int block = 0; block < 10; ++block) {
    SphereMover mover;
    mover.reset(s.xyz.data(), s.radius.data(), s.size(), s.box, d_max, kTol);
    const CounterRandom rng(77, static_cast<std::uint64_t>(block));
    TrialTally tally;
    mover.run(ids.data(), s.size(), PickOrder::Random, cursor, sampler, rng, 0, 1000000, nullptr,
              tally);
    accepted += tally.accepted;
    for (int i = 0; i < s.size(); ++i)
      for (int d = 0; d < 3; ++d) s.xyz[3 * i + d] = mover.position(i)[d];
    const OracleReport rep = brute_force_check(s.xyz.data(), s.radius.data(), s.size(), s.box, kTol);
    ASSERT_EQ(rep.pair_overlaps, 0) << "block " << block << " worst gap " << rep.worst_gap;
    ASSERT_EQ(rep.plane_violations, 0) << "block " << block << " worst gap " << rep.worst_gap;
    EXPECT_EQ(mover.check_lists(), "") << "block " << block;
    for (int i = 0; i < s.size(); ++i) {
      const double dx = s.xyz[3 * i] - s.box.cylinder_cx, dy = s.xyz[3 * i + 1] - s.box.cylinder_cy;
      at_wall += (s.box.cylinder_radius - s.radius[i]) - std::sqrt(dx * dx + dy * dy) < 1e-2;
    }
    dilate(s, 0.2);
  }
  // the wall was tested by moves, not by a frozen packing: tens of thousands of accepted moves,
  // and spheres within 1 % of a radius of the wall after the blocks
  EXPECT_GT(accepted, 30000);
  EXPECT_GT(at_wall, 10);
}

// A container needs non-periodic sides and room for its largest sphere; the messages name the
// argument and its value.
TEST(SphereMover, CylinderArgumentsAreChecked)
{
  Scene s = in_cylinder(random_loose(60, 4.0, 0.5, false, false, 3, 0.25), 2.0);
  SphereMover mover;
  SettleBox periodic = s.box;
  periodic.periodic[0] = true;
  try {
    mover.reset(s.xyz.data(), s.radius.data(), s.size(), periodic, 0.1, kTol);
    FAIL() << "a periodic axis with a cylinder was accepted";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("non-periodic x and y"), std::string::npos) << e.what();
  }
  SettleBox narrow = s.box;
  narrow.cylinder_radius = 0.4;
  try {
    mover.reset(s.xyz.data(), s.radius.data(), s.size(), narrow, 0.1, kTol);
    FAIL() << "a cylinder narrower than a sphere was accepted";
  } catch (const std::invalid_argument &e) {
    EXPECT_NE(std::string(e.what()).find("cylinder radius = 0.4"), std::string::npos) << e.what();
  }
}
