// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the counter-based random numbers: published answers, keying, uniformity.
#include "mc_test_stats.h"
#include "tapmc_random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

using namespace tapmc;
using namespace tapmc::test_stats;

// Known-answer vectors of Philox-4x32-10 published with the algorithm (Random123 kat_vectors).
TEST(Random, PhiloxMatchesPublishedKnownAnswers)
{
  EXPECT_EQ(philox4x32_10({0, 0, 0, 0}, 0, 0),
            (RandomBlock{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}));
  EXPECT_EQ(philox4x32_10({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}, 0xffffffffu,
                          0xffffffffu),
            (RandomBlock{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}));
  EXPECT_EQ(philox4x32_10({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}, 0xa4093822u,
                          0x299f31d0u),
            (RandomBlock{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}));
}

TEST(Random, ReproducibleWithoutState)
{
  const CounterRandom a(12345, 678), b(12345, 678);
  for (std::uint64_t k : {0ull, 1ull, 99ull, 1ull << 40, ~0ull}) {
    EXPECT_EQ(a.block(k), b.block(k));
    EXPECT_EQ(a.uniform(k), b.uniform(k));
  }
  // Order of evaluation does not matter: position 7 is the same before and after others.
  const RandomBlock first = a.block(7);
  for (int k = 0; k < 100; ++k) a.block(k);
  EXPECT_EQ(a.block(7), first);
}

// Seed, stream and position each change the block; all 64 bits of seed, stream and position
// are used (flipping any single bit changes the output).
TEST(Random, EveryKeyBitMatters)
{
  const std::uint64_t seed = 0x0123456789abcdefull, stream = 0xfedcba9876543210ull, pos = 42;
  const RandomBlock base = CounterRandom(seed, stream).block(pos);
  std::set<RandomBlock> seen{base};
  for (int bit = 0; bit < 64; ++bit) {
    const std::uint64_t m = std::uint64_t{1} << bit;
    seen.insert(CounterRandom(seed ^ m, stream).block(pos));
    seen.insert(CounterRandom(seed, stream ^ m).block(pos));
    seen.insert(CounterRandom(seed, stream).block(pos ^ m));
  }
  EXPECT_EQ(seen.size(), 1u + 3u * 64u);
}

// Neighbouring seeds / streams give uncorrelated sequences (sample correlation within 5 sigma).
TEST(Random, NeighbouringKeysAreUncorrelated)
{
  const int n = 200000;
  const CounterRandom a(1, 1), b(2, 1), c(1, 2);
  double sab = 0, sac = 0;
  for (int k = 0; k < n; ++k) {
    const double u = a.uniform(k) - 0.5, v = b.uniform(k) - 0.5, w = c.uniform(k) - 0.5;
    sab += u * v;
    sac += u * w;
  }
  // E[uv] = 0, sd of the mean of uv = (1/12) / sqrt(n)
  const double sigma = (1.0 / 12.0) / std::sqrt(static_cast<double>(n));
  EXPECT_LT(std::fabs(sab / n), 5 * sigma);
  EXPECT_LT(std::fabs(sac / n), 5 * sigma);
}

TEST(Random, UniformDoublesPassChiSquareAndMoments)
{
  for (std::uint64_t seed : {1ull, 77ull, 123456789ull}) {
    const CounterRandom rng(seed, 5);
    const int bins = 100, n = 1000000;
    std::vector<long> counts(bins, 0);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
      const double u = rng.uniform(k);
      ASSERT_GE(u, 0.0);
      ASSERT_LT(u, 1.0);
      ++counts[static_cast<int>(u * bins)];
      sum += u;
      sum2 += u * u;
    }
    const double chi2 = chi_square(counts, std::vector<double>(bins, double(n) / bins));
    EXPECT_TRUE(chi_square_plausible(chi2, bins - 1)) << "seed " << seed << " chi2 " << chi2;
    const double mean = sum / n, var = sum2 / n - mean * mean;
    EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
    EXPECT_NEAR(var, 1.0 / 12.0, 5 * std::sqrt(1.0 / 180.0 / n));  // var of u^2 ... ~1/180
  }
}

// Each of the four words is uniform on its own (top byte, 256 bins).
TEST(Random, EachWordIsUniform)
{
  const CounterRandom rng(99, 0);
  const int n = 300000;
  std::vector<std::vector<long>> counts(4, std::vector<long>(256, 0));
  for (int k = 0; k < n; ++k) {
    const RandomBlock b = rng.block(k);
    for (int w = 0; w < 4; ++w) ++counts[w][b[w] >> 24];
  }
  for (int w = 0; w < 4; ++w) {
    const double chi2 = chi_square(counts[w], std::vector<double>(256, n / 256.0));
    EXPECT_TRUE(chi_square_plausible(chi2, 255)) << "word " << w << " chi2 " << chi2;
  }
}

TEST(Random, ConversionsStayInTheirIntervals)
{
  EXPECT_EQ(uniform_from_u64(0), 0.0);
  EXPECT_LT(uniform_from_u64(~0ull), 1.0);
  EXPECT_EQ(uniform_from_u32(0), 0.0);
  EXPECT_LT(uniform_from_u32(0xffffffffu), 1.0);
  EXPECT_GT(uniform_open_from_u32(0), 0.0);
  EXPECT_LT(uniform_open_from_u32(0xffffffffu), 1.0);
}

// bounded_index is exactly uniform: for n = 3 (2^32 mod 3 = 1) the rejected zone is one word
// per residue class, checked on the words that land there; and chi-square for n = 7 and 1000.
TEST(Random, BoundedIndexIsUniformAndRejectsTheBiasZone)
{
  std::uint32_t idx = 0;
  // n = 3: threshold = 2^32 mod 3 = 1; the only rejected word is the one with low part 0.
  EXPECT_FALSE(bounded_index(0u, 3u, idx));
  EXPECT_TRUE(bounded_index(1u, 3u, idx));
  EXPECT_EQ(idx, 0u);
  EXPECT_TRUE(bounded_index(0xffffffffu, 3u, idx));
  EXPECT_EQ(idx, 2u);
  EXPECT_TRUE(bounded_index(0xffffffffu, 1u, idx));
  EXPECT_EQ(idx, 0u);
  for (std::uint32_t n : {7u, 1000u}) {
    const CounterRandom rng(3, n);
    const int draws = 500000;
    std::vector<long> counts(n, 0);
    int rejected = 0;
    for (int k = 0; k < draws; ++k) {
      if (!bounded_index(rng.block(k)[0], n, idx)) {
        ++rejected;
        continue;
      }
      ASSERT_LT(idx, n);
      ++counts[idx];
    }
    const double chi2 = chi_square(counts, std::vector<double>(n, double(draws - rejected) / n));
    EXPECT_TRUE(chi_square_plausible(chi2, n - 1)) << "n " << n << " chi2 " << chi2;
    EXPECT_LE(rejected, 3);  // probability < n / 2^32 per draw
  }
}

// Purposes: purpose 0 (the Monte Carlo moves) is the plain stream; the other purposes draw other
// blocks for the same (seed, stream, position), and a stream id beyond 2^56 stays in its purpose.
TEST(Random, PurposesNeverShareABlock)
{
  const std::uint64_t seed = 4928, stream = 77, position = 5;
  EXPECT_EQ(CounterRandom(seed, RandomPurpose::kSettleMoves, stream).block(position),
            CounterRandom(seed, stream).block(position));
  std::set<RandomBlock> seen;
  for (RandomPurpose purpose : {RandomPurpose::kSettleMoves, RandomPurpose::kDepositionDrops,
                                RandomPurpose::kDepositionEquilibria,
                                RandomPurpose::kPoreSamplePoints})
    seen.insert(CounterRandom(seed, purpose, stream).block(position));
  EXPECT_EQ(seen.size(), 4u);
  // The purpose byte is the top byte of the stream word.
  EXPECT_EQ(CounterRandom(seed, RandomPurpose::kDepositionDrops, stream).block(position),
            CounterRandom(seed, (std::uint64_t(1) << 56) | stream).block(position));
  EXPECT_EQ(CounterRandom(seed, RandomPurpose::kSettleMoves, kMaxPurposeStream + stream)
                .block(position),
            CounterRandom(seed, stream).block(position));
}
