// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Trial displacement of the redeposition: strip tables of the theta sampler, the full draw.
#include "tapmc_trial_move.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace tapmc {

namespace {

constexpr double kTwoPi = 6.28318530717958647693;
constexpr double kSqrtPi = 1.77245385090551602730;

std::string number(double value)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

}  // namespace

ThetaSampler::ThetaSampler(double theta0) : theta0_(theta0)
{
  if (!(theta0 > 0.0 && theta0 <= kThetaMax))
    throw std::invalid_argument("theta0 = " + number(theta0) +
                                " is outside the allowed range (0, pi/2]");
  inv_theta0_sq_ = 1.0 / (theta0 * theta0);
  norm_ = std::erf(kThetaMax / theta0);
  // Equal-probability strip edges: cdf(edge_k) = k / kStrips, by bisection (cdf is strictly
  // increasing; 100 halvings reach the double resolution of [0, pi/2]).
  edge_[0] = 0.0;
  edge_[kStrips] = kThetaMax;
  for (int k = 1; k < kStrips; ++k) {
    const double target = static_cast<double>(k) / kStrips;
    double lo = edge_[k - 1], hi = kThetaMax;
    for (int it = 0; it < 100 && hi - lo > 0.0; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      if (cdf(mid) < target)
        lo = mid;
      else
        hi = mid;
    }
    edge_[k] = 0.5 * (lo + hi);
  }
  for (int k = 0; k < kStrips; ++k) {
    width_[k] = edge_[k + 1] - edge_[k];
    const double l = edge_[k], r = edge_[k + 1];
    squeeze_[k] = std::exp(-(r - l) * (r + l) * inv_theta0_sq_);  // P(right) / P(left)
  }
}

double ThetaSampler::density(double theta) const
{
  if (theta < 0.0 || theta > kThetaMax) return 0.0;
  // A = 2 / (sqrt(pi) theta0 erf(pi / (2 theta0))) normalises eq. 1 on [0, pi/2].
  return 2.0 / (kSqrtPi * theta0_ * norm_) * std::exp(-theta * theta * inv_theta0_sq_);
}

double ThetaSampler::cdf(double theta) const
{
  if (theta <= 0.0) return 0.0;
  if (theta >= kThetaMax) return 1.0;
  return std::erf(theta / theta0_) / norm_;
}

double ThetaSampler::exp_fraction() const
{
  double sum = 0.0;
  for (int k = 0; k < kStrips; ++k) sum += 1.0 - squeeze_[k];
  return sum / kStrips;
}

SinCosTable::SinCosTable(double range) : step_(range / kNodes), inv_step_(kNodes / range)
{
  for (int j = 0; j <= kNodes; ++j) {
    node_[j] = j * step_;
    sin_[j] = std::sin(node_[j]);
    cos_[j] = std::cos(node_[j]);
  }
}

TrialMoveSampler::TrialMoveSampler(double d_max, double theta0)
    : d_max_(d_max), theta_(theta0), phi_table_(kTwoPi), theta_table_(ThetaSampler::kThetaMax)
{
  if (!(d_max > 0.0 && std::isfinite(d_max)))
    throw std::invalid_argument("d_max = " + number(d_max) +
                                " is outside the allowed range (0, +inf)");
}

namespace {

// Positions within one trial's slice of the stream.
constexpr std::uint64_t kMainDraw = 0;         // pick, d, phi, theta strip
constexpr std::uint64_t kFirstThetaDraw = 1;   // two (position, accept) pairs per block
constexpr std::uint64_t kFirstPickDraw = 128;  // fresh words for the rare pick rejection

std::uint32_t sample_pick(const CounterRandom &rng, std::uint64_t base, std::uint32_t first_word,
                          std::uint32_t n_pick)
{
  std::uint32_t index = 0;
  if (bounded_index(first_word, n_pick, index)) return index;
  for (std::uint64_t draw = kFirstPickDraw; draw < TrialMoveSampler::kDrawsPerTrial; ++draw) {
    const RandomBlock block = rng.block(base + draw);
    for (std::uint32_t word : block)
      if (bounded_index(word, n_pick, index)) return index;
  }
  throw std::runtime_error("sphere pick exhausted its random draws (impossible odds)");
}

}  // namespace

double TrialMoveSampler::theta_from(const CounterRandom &rng, std::uint64_t trial,
                                    std::uint32_t strip_word, const RandomBlock &theta_first) const
{
  const std::uint64_t base = trial * kDrawsPerTrial;
  std::uint64_t attempt = 0;
  RandomBlock block = theta_first;
  return theta_.sample(strip_word, [&](std::uint32_t &w_pos, std::uint32_t &w_accept) {
    const std::uint64_t draw = kFirstThetaDraw + attempt / 2;
    if (draw >= kFirstPickDraw)  // needs > 250 consecutive rejections
      throw std::runtime_error("theta sampler exhausted its random draws (impossible odds)");
    if (attempt % 2 == 0) {
      if (attempt > 0) block = rng.block(base + draw);
      w_pos = block[0];
      w_accept = block[1];
    } else {
      w_pos = block[2];
      w_accept = block[3];
    }
    ++attempt;
  });
}

TrialDraw TrialMoveSampler::finish(const CounterRandom &rng, std::uint64_t trial,
                                   std::uint32_t n_pick, const RandomBlock &main,
                                   const RandomBlock &theta_first) const
{
  TrialDraw out{};
  out.pick = n_pick ? sample_pick(rng, trial * kDrawsPerTrial, main[0], n_pick) : 0u;
  const double d = d_max_ * uniform_open_from_u32(main[1]);
  // phi = 2 pi main[2] / 2^32 = sector (top 8 bits) + offset (low 24 bits), both exact.
  const int sector = static_cast<int>(main[2] >> 24);
  const double phi_offset = static_cast<double>(main[2] & 0xFFFFFFu) * (kTwoPi * 0x1.0p-32);
  double sin_phi, cos_phi, sin_theta, cos_theta;
  phi_table_.rotate(sector, phi_offset, sin_phi, cos_phi);
  theta_table_.sincos(theta_from(rng, trial, main[3], theta_first), sin_theta, cos_theta);
  // theta <= pi/2, so cos(theta) >= 0 up to rounding (~1e-17 at pi/2): the clamp keeps
  // dz <= 0 exactly, moves never go up.
  const double d_sin = d * sin_theta;
  out.move.dx = d_sin * cos_phi;
  out.move.dy = d_sin * sin_phi;
  out.move.dz = -d * std::max(cos_theta, 0.0);
  return out;
}

TrialDraw TrialMoveSampler::draw(const CounterRandom &rng, std::uint64_t trial,
                                 std::uint32_t n_pick) const
{
  const std::uint64_t base = trial * kDrawsPerTrial;
  return finish(rng, trial, n_pick, rng.block(base + kMainDraw), rng.block(base + kFirstThetaDraw));
}

void TrialMoveSampler::draw_batch(const CounterRandom &rng, std::uint64_t first, int count,
                                  std::uint32_t n_pick, TrialDraw *out) const
{
  if (count < 0 || count > kBatchMax)
    throw std::invalid_argument("draw_batch count = " + std::to_string(count) +
                                " is outside the allowed range [0, " +
                                std::to_string(kBatchMax) + "]");
  std::uint64_t positions[2 * kBatchMax];
  RandomBlock blocks[2 * kBatchMax];
  for (int k = 0; k < count; ++k) {
    const std::uint64_t base = (first + k) * kDrawsPerTrial;
    positions[k] = base + kMainDraw;
    positions[count + k] = base + kFirstThetaDraw;
  }
  rng.blocks(positions, 2 * count, blocks);
  for (int k = 0; k < count; ++k)
    out[k] = finish(rng, first + k, n_pick, blocks[k], blocks[count + k]);
}

TrialMoveSampler::Polar TrialMoveSampler::draw_polar(const CounterRandom &rng,
                                                     std::uint64_t trial) const
{
  const std::uint64_t base = trial * kDrawsPerTrial;
  const RandomBlock main = rng.block(base + kMainDraw);
  Polar out{};
  out.d = d_max_ * uniform_open_from_u32(main[1]);
  out.phi = kTwoPi * uniform_from_u32(main[2]);
  out.theta = theta_from(rng, trial, main[3], rng.block(base + kFirstThetaDraw));
  return out;
}

}  // namespace tapmc
