// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Counter-based random numbers (Philox-4x32-10, Salmon et al., SC'11): a keyed pure function of
// (seed, stream, counter), no stored state, so a restarted run draws exactly the same numbers.
#ifndef TAPMC_RANDOM_H
#define TAPMC_RANDOM_H

#include <array>
#include <cstdint>

namespace tapmc {

using RandomBlock = std::array<std::uint32_t, 4>;

// Philox-4x32 with 10 rounds, implemented from the published algorithm (Salmon, Moraes, Dror,
// Shaw, "Parallel random numbers: as easy as 1, 2, 3", SC'11, section 3.2). Each round
// multiplies two counter words by fixed odd constants and mixes the 64-bit products' halves
// with the other words and the round key; the key is bumped by Weyl constants between rounds.
// Crush-resistant with 10 rounds (the paper's recommended count).
namespace philox {
constexpr int kRounds = 10;
constexpr std::uint64_t kMul0 = 0xD2511F53u, kMul1 = 0xCD9E8D57u;
constexpr std::uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;

// One round on the counter words c0..c3 under the round key (k0, k1).
inline void round(std::uint32_t &c0, std::uint32_t &c1, std::uint32_t &c2, std::uint32_t &c3,
                  std::uint32_t k0, std::uint32_t k1)
{
  const std::uint64_t p0 = kMul0 * c0;
  const std::uint64_t p1 = kMul1 * c2;
  const std::uint32_t n0 = static_cast<std::uint32_t>(p1 >> 32) ^ c1 ^ k0;
  const std::uint32_t n2 = static_cast<std::uint32_t>(p0 >> 32) ^ c3 ^ k1;
  c1 = static_cast<std::uint32_t>(p1);
  c3 = static_cast<std::uint32_t>(p0);
  c0 = n0;
  c2 = n2;
}
}  // namespace philox

inline RandomBlock philox4x32_10(RandomBlock counter, std::uint32_t key0, std::uint32_t key1)
{
  std::uint32_t c0 = counter[0], c1 = counter[1], c2 = counter[2], c3 = counter[3];
  for (int r = 0; r < philox::kRounds; ++r) {
    philox::round(c0, c1, c2, c3, key0, key1);
    key0 += philox::kWeyl0;
    key1 += philox::kWeyl1;
  }
  return {c0, c1, c2, c3};
}

// Uniform double in [0, 1) with 53 random bits (the top 53 of the 64-bit word).
inline double uniform_from_u64(std::uint64_t word)
{
  return static_cast<double>(word >> 11) * 0x1.0p-53;
}

// Uniform double in [0, 1) with 32 random bits: k / 2^32, k in [0, 2^32).
inline double uniform_from_u32(std::uint32_t word)
{
  return static_cast<double>(word) * 0x1.0p-32;
}

// Uniform double in the open interval (0, 1): (k + 1/2) / 2^32; never 0, never 1.
inline double uniform_open_from_u32(std::uint32_t word)
{
  return (static_cast<double>(word) + 0.5) * 0x1.0p-32;
}

inline std::uint64_t join_u32(std::uint32_t hi, std::uint32_t lo)
{
  return (static_cast<std::uint64_t>(hi) << 32) | lo;
}

// What a stream of random numbers is for, one constant per use of the package (as HOOMD-blue
// gives each use its own identifier): the purpose fills the top byte of the stream word of the
// counter, so two uses never draw the same (key, counter) pair, whatever their seeds and stream
// ids (stream ids stay below kMaxPurposeStream). Every random draw of the product names its
// purpose here.
enum class RandomPurpose : std::uint8_t {
  kSettleMoves = 0,             // fix mc/settle trial moves; stream: the timestep of the tap
  kDepositionDrops = 1,         // create_packing: sphere i's radius and drop points; stream: i
  kDepositionEquilibria = 2,    // create_packing: directions that leave unstable equilibria
                                // while sphere i descends; stream: i
  kPoreSamplePoints = 3,        // tapmc-pores --p0: the sample points; stream: the frame
  kDomainSettleMoves = 4,       // fix mc/settle scheme domain: trial moves of one sub-domain
                                // (key round sub_domain_key_index, tapmc_decomposition.h); stream:
                                // the timestep of the tap
  kDomainSettleCuts = 5,        // fix mc/settle scheme domain: the cuts of every cycle of rounds;
                                // stream: the timestep of the tap
};
constexpr int kPurposeShift = 56;  // bits of the stream word below the purpose byte
constexpr std::uint64_t kMaxPurposeStream = std::uint64_t(1) << kPurposeShift;

// A keyed stream of blocks. Key = 64-bit user seed; the 128-bit counter holds the 64-bit
// stream id (e.g. the LAMMPS timestep of a tap) and a 64-bit position within the stream,
// so (seed, stream, position) -> block is injective and needs no state.
class CounterRandom {
 public:
  CounterRandom(std::uint64_t seed, std::uint64_t stream)
      : key0_(static_cast<std::uint32_t>(seed)), key1_(static_cast<std::uint32_t>(seed >> 32)),
        stream_lo_(static_cast<std::uint32_t>(stream)),
        stream_hi_(static_cast<std::uint32_t>(stream >> 32))
  {
  }

  // The stream `stream` of one purpose: the stream word is purpose * 2^56 + (stream mod 2^56)
  // (a stream id at or above kMaxPurposeStream would reuse a smaller one of its own purpose,
  // never another purpose's). With kSettleMoves (0) this is the plain stream.
  CounterRandom(std::uint64_t seed, RandomPurpose purpose, std::uint64_t stream)
      : CounterRandom(seed, (static_cast<std::uint64_t>(purpose) << kPurposeShift) |
                                (stream & (kMaxPurposeStream - 1)))
  {
  }

  // Four independent 32-bit words for position `position` of this stream.
  RandomBlock block(std::uint64_t position) const
  {
    return philox4x32_10({static_cast<std::uint32_t>(position),
                          static_cast<std::uint32_t>(position >> 32), stream_lo_, stream_hi_},
                         key0_, key1_);
  }

  // block(positions[k]) for k < count, computed lane-parallel (the loop over lanes inside each
  // round vectorises), bit-identical to block(). count <= kBatchMax.
  static constexpr int kBatchMax = 256;
  void blocks(const std::uint64_t *positions, int count, RandomBlock *out) const
  {
    alignas(64) std::uint32_t c0[kBatchMax], c1[kBatchMax], c2[kBatchMax], c3[kBatchMax];
    for (int k = 0; k < count; ++k) {
      c0[k] = static_cast<std::uint32_t>(positions[k]);
      c1[k] = static_cast<std::uint32_t>(positions[k] >> 32);
      c2[k] = stream_lo_;
      c3[k] = stream_hi_;
    }
    std::uint32_t k0 = key0_, k1 = key1_;
    for (int r = 0; r < philox::kRounds; ++r) {
      for (int k = 0; k < count; ++k) philox::round(c0[k], c1[k], c2[k], c3[k], k0, k1);
      k0 += philox::kWeyl0;
      k1 += philox::kWeyl1;
    }
    for (int k = 0; k < count; ++k) out[k] = {c0[k], c1[k], c2[k], c3[k]};
  }

  // The same stream under the key seed + round * 0x9E3779B97F4A7C15 (mod 2^64): for a fixed
  // seed, the keys of rounds 0 .. 2^64 - 1 are all distinct (the constant is odd), so an
  // overflow round never reuses a (key, counter) pair of the stream itself. round 0 = *this.
  CounterRandom round(std::uint64_t round_index) const
  {
    constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;
    const std::uint64_t seed = join_u32(key1_, key0_) + round_index * kGolden;
    return CounterRandom(seed, join_u32(stream_hi_, stream_lo_));
  }

  // Uniform double in [0, 1) (53 bits) from the first two words of block(position).
  double uniform(std::uint64_t position) const
  {
    const RandomBlock b = block(position);
    return uniform_from_u64(join_u32(b[0], b[1]));
  }

 private:
  std::uint32_t key0_, key1_, stream_lo_, stream_hi_;
};

// Unbiased integer in [0, n) from a 32-bit word by multiply-shift (Lemire, ACM TOMACS 2019).
// Returns false when the word falls in the small rejected zone (probability < n / 2^32); the
// caller then draws a fresh word. n must be in [1, 2^32).
inline bool bounded_index(std::uint32_t word, std::uint32_t n, std::uint32_t &index)
{
  const std::uint64_t product = static_cast<std::uint64_t>(word) * n;
  const std::uint32_t low = static_cast<std::uint32_t>(product);
  if (low < n) {
    const std::uint32_t threshold = static_cast<std::uint32_t>(-n) % n;  // 2^32 mod n
    if (low < threshold) return false;
  }
  index = static_cast<std::uint32_t>(product >> 32);
  return true;
}

}  // namespace tapmc

#endif
