// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The rounds of the decomposed redeposition (tapmc_decomposition.h): on explicit processor grids
// with periodic images, regions moved in the same round never come within a contact distance of
// each other, every sphere a rank owns lies in the region of the round it is active in, and the
// trial counts give every sphere the serial pick probability.
#include "tapmc_decomposition.h"
#include "tapmc_random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tapmc;

namespace {

struct Grid {
  int procs[3];
  bool periodic[3];
  double length[3];
};

std::array<DecomposedAxis, 3> axes_of(const Grid &g, const int cell[3])
{
  std::array<DecomposedAxis, 3> axes;
  for (int d = 0; d < 3; ++d) {
    const double w = g.length[d] / g.procs[d];
    axes[d].split = g.procs[d] > 1 || g.periodic[d];
    axes[d].lo = cell[d] * w;
    axes[d].hi = (cell[d] + 1) * w;
    axes[d].min_width = w;
  }
  return axes;
}

// Gap between [a_lo, a_hi) and [b_lo, b_hi) (negative when they overlap).
double gap(double a_lo, double a_hi, double b_lo, double b_hi)
{
  return std::max(b_lo - a_hi, a_lo - b_hi);
}

// Every pair of (rank, periodic image) regions of the same round is `contact` apart along some
// axis, over many random cuts.
void expect_rounds_separated(const Grid &g, double contact, double margin, int cycles)
{
  std::vector<std::array<int, 3>> cells;
  for (int i = 0; i < g.procs[0]; ++i)
    for (int j = 0; j < g.procs[1]; ++j)
      for (int k = 0; k < g.procs[2]; ++k) cells.push_back({i, j, k});
  const CounterRandom rng(99, 7);
  for (int cycle = 0; cycle < cycles; ++cycle) {
    const std::array<double, 3> u = {rng.uniform(3 * cycle), rng.uniform(3 * cycle + 1),
                                     rng.uniform(3 * cycle + 2)};
    std::vector<RoundSchedule> schedules;
    for (const auto &c : cells) {
      schedules.emplace_back(axes_of(g, c.data()), contact, margin);
      schedules.back().start_cycle(u);
    }
    const int rounds = schedules[0].rounds();
    for (int r = 0; r < rounds; ++r)
      for (std::size_t a = 0; a < cells.size(); ++a)
        for (std::size_t b = 0; b < cells.size(); ++b)
          for (int sx = -1; sx <= 1; ++sx)
            for (int sy = -1; sy <= 1; ++sy) {
              const int shift[3] = {sx, sy, 0};
              if (a == b && sx == 0 && sy == 0) continue;
              if ((sx && !g.periodic[0]) || (sy && !g.periodic[1])) continue;
              const MoveRegion ra = schedules[a].region(r), rb = schedules[b].region(r);
              double best = -1e300;
              for (int d = 0; d < 3; ++d) {
                const double s = shift[d] * g.length[d];
                best = std::max(best, gap(ra.lo[d], ra.hi[d], rb.lo[d] + s, rb.hi[d] + s));
              }
              // Rounding of the region bounds (~1e-16 relative) stays far below the contact
              // tolerance (an overlap needs a distance below contact * (1 - 1e-10)).
              ASSERT_GE(best, contact * (1.0 - 1e-13)) << "round " << r << " ranks " << a << ", " << b
                                       << " image (" << sx << ", " << sy << ") cycle " << cycle;
            }
  }
}

}  // namespace

TEST(RoundSchedule, RegionsOfOneRoundNeverTouchAcrossRanksOrImages)
{
  const double contact = 2.0, margin = 0.8;
  // 1, 2, 3, 4 ranks along x; x-y grids; walls (non-periodic x); a split z.
  expect_rounds_separated({{1, 1, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{2, 1, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{3, 1, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{4, 1, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{2, 2, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{1, 4, 1}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{2, 2, 1}, {false, false, false}, {32, 32, 40}}, contact, margin, 50);
  expect_rounds_separated({{2, 1, 2}, {true, true, false}, {32, 32, 40}}, contact, margin, 50);
  // The narrowest allowed sub-domain: 2 contact + 4 margin.
  const double w = RoundSchedule::min_width(contact, margin);
  expect_rounds_separated({{3, 2, 1}, {true, true, false}, {3 * w, 2 * w, 40}}, contact, margin,
                          50);
}

TEST(RoundSchedule, EveryOwnedSphereLiesInTheRegionOfItsRound)
{
  const Grid g{{2, 2, 1}, {true, false, false}, {32, 24, 40}};
  const double contact = 2.0, margin = 0.8;
  const CounterRandom rng(5, 1);
  std::uint64_t draw = 0;
  for (int cx = 0; cx < 2; ++cx)
    for (int cy = 0; cy < 2; ++cy) {
      const int cell[3] = {cx, cy, 0};
      const auto axes = axes_of(g, cell);
      RoundSchedule schedule(axes, contact, margin);
      EXPECT_EQ(schedule.rounds(), 4);
      std::vector<int> count(4, 0);
      for (int cycle = 0; cycle < 20; ++cycle) {
        schedule.start_cycle({rng.uniform(draw++), rng.uniform(draw++), 0.0});
        for (int p = 0; p < 2000; ++p) {
          // owned spheres may lie up to the margin outside the sub-domain (moved there)
          double xyz[3];
          for (int d = 0; d < 3; ++d) {
            const double lo = axes[d].lo - margin, hi = axes[d].hi + margin;
            xyz[d] = lo + (hi - lo) * rng.uniform(draw++);
          }
          const int round = schedule.round_of(xyz);
          ASSERT_GE(round, 0);
          ASSERT_LT(round, 4);
          ++count[round];
          const MoveRegion r = schedule.region(round);
          for (int d = 0; d < 3; ++d) {
            EXPECT_GE(xyz[d], r.lo[d]);
            EXPECT_LT(xyz[d], r.hi[d]);
          }
        }
      }
      for (int round = 0; round < 4; ++round) EXPECT_GT(count[round], 0);
    }
}

TEST(RoundSchedule, CutsSpreadOverTheirWholeAllowedRange)
{
  const Grid g{{2, 1, 1}, {true, true, false}, {32, 32, 40}};
  const int cell[3] = {1, 0, 0};
  RoundSchedule schedule(axes_of(g, cell), 2.0, 0.8);
  schedule.start_cycle({0.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(schedule.cut(0), 16.0 + 2.0 + 1.6);
  schedule.start_cycle({1.0, 1.0, 0.0});
  EXPECT_DOUBLE_EQ(schedule.cut(0), 32.0 - 2.0 - 1.6);
  EXPECT_DOUBLE_EQ(schedule.cut(1), 32.0 - 2.0 - 1.6);
}

TEST(RoundSchedule, TooNarrowSubDomainIsRefusedNamingTheAxis)
{
  const Grid g{{1, 8, 1}, {true, true, false}, {32, 32, 40}};  // 4 wide along y < 7.2
  const int cell[3] = {0, 3, 0};
  try {
    RoundSchedule schedule(axes_of(g, cell), 2.0, 0.8);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument &e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("along y is 4 wide"), std::string::npos) << what;
    EXPECT_NE(what.find("7.2"), std::string::npos) << what;
  }
  EXPECT_THROW(RoundSchedule(axes_of(g, cell), 0.0, 0.8), std::invalid_argument);
  EXPECT_THROW(RoundSchedule(axes_of(g, cell), 2.0, -1.0), std::invalid_argument);
}

TEST(RoundSchedule, NoSplitAxisMeansOneUnboundedRound)
{
  const Grid g{{1, 1, 1}, {false, false, false}, {32, 32, 40}};
  const int cell[3] = {0, 0, 0};
  RoundSchedule schedule(axes_of(g, cell), 2.0, 0.8);
  EXPECT_EQ(schedule.rounds(), 1);
  const double far[3] = {-1e9, 1e9, 5};
  EXPECT_EQ(schedule.round_of(far), 0);
  const MoveRegion r = schedule.region(0);
  EXPECT_LT(r.lo[0], -1e300);
  EXPECT_GT(r.hi[2], 1e300);
}

TEST(RoundTrials, EverySphereExpectsTheSerialNumberOfPicksPerCycle)
{
  // One sweep per check: each rank makes exactly as many trials as it has active spheres.
  EXPECT_EQ(round_trials(100, 517, 4096, 4096), 517);
  EXPECT_EQ(round_trials(100, 0, 4096, 4096), 0);
  // A check interval of 2 sweeps doubles them; a tenth of a sweep: 51 or 52 of 51.75.
  EXPECT_EQ(round_trials(0, 517, 8192, 4096), 1034);
  EXPECT_EQ(round_trials(0, 517, 410, 4096), 51);
  EXPECT_EQ(round_trials(3, 517, 410, 4096), 52);
  // Summed over the parts of a partition (in their numbering), the trials of a cycle are the
  // check interval exactly, also when every part's share is below one trial (500 spheres in
  // 16 parts, check 5: the shares of 0.31 each rounded to nearest made none).
  for (long interval : {1L, 5L, 7L, 250L, 1234L, 4096L, 9999L}) {
    const long parts[16] = {31, 32, 30, 33, 31, 29, 34, 30, 32, 31, 30, 33, 31, 32, 30, 31};
    long before = 0, sum = 0;
    for (long p : parts) {
      const long share = round_trials(before, p, interval, 500);
      EXPECT_LE(std::fabs(share - static_cast<double>(p) * interval / 500.0), 1.0);
      sum += share;
      before += p;
    }
    EXPECT_EQ(before, 500);
    EXPECT_EQ(sum, interval) << "check " << interval;
  }
  // Large counts do not overflow: 2^31 spheres, a check of 3 * 2^31 trials.
  const long big = 1L << 31;
  EXPECT_EQ(round_trials(big / 2, big / 2, 3 * big, big), 3 * (big / 2));
}

TEST(RandomKeys, SubDomainsDrawFromDisjointKeys)
{
  EXPECT_NE(sub_domain_key_index(0), 0u);  // never the un-rounded key
  EXPECT_EQ(sub_domain_key_index(1) - sub_domain_key_index(0), std::uint64_t{1} << 32);
  const CounterRandom base(42, RandomPurpose::kDomainSettleMoves, 1000);
  EXPECT_NE(base.round(sub_domain_key_index(0)).block(0),
            base.round(sub_domain_key_index(1)).block(0));
  EXPECT_NE(base.round(sub_domain_key_index(0)).block(0), base.block(0));
  EXPECT_NE(CounterRandom(42, RandomPurpose::kDomainSettleCuts, 1000).block(0), base.block(0));
}

// The sub-domains of a grid are numbered 0 .. P-1 once each, z fastest: the ranks of MPI's
// row-major Cartesian order (LAMMPS's default 'map cart'), whatever rank holds them.
TEST(RandomKeys, SubDomainNumbersAreTheCartesianRanks)
{
  const int grid[3] = {2, 3, 2};
  int expected = 0;
  for (int x = 0; x < grid[0]; ++x)
    for (int y = 0; y < grid[1]; ++y)
      for (int z = 0; z < grid[2]; ++z) {
        const int loc[3] = {x, y, z};
        EXPECT_EQ(sub_domain_number(loc, grid), expected++);
      }
  const int one[3] = {1, 1, 1}, origin[3] = {0, 0, 0};
  EXPECT_EQ(sub_domain_number(origin, one), 0);
}
