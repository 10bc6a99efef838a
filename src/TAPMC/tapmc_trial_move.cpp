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

TrialMoveSampler::TrialMoveSampler(double d_max, double theta0) : d_max_(d_max), theta_(theta0)
{
  if (!(d_max > 0.0 && std::isfinite(d_max)))
    throw std::invalid_argument("d_max = " + number(d_max) +
                                " is outside the allowed range (0, +inf)");
}

namespace {

// Positions within one trial's slice of the stream.
constexpr std::uint64_t kMainDraw = 0;        // pick, d, phi, theta strip
constexpr std::uint64_t kFirstThetaDraw = 1;  // two (position, accept) pairs per block
constexpr std::uint64_t kFirstPickDraw = 128; // fresh words for the rare pick rejection

double sample_theta(const ThetaSampler &sampler, const CounterRandom &rng, std::uint64_t base,
                    std::uint32_t strip_word)
{
  std::uint64_t attempt = 0;
  RandomBlock block{};
  return sampler.sample(strip_word, [&](std::uint32_t &w_pos, std::uint32_t &w_accept) {
    const std::uint64_t draw = kFirstThetaDraw + attempt / 2;
    if (draw >= kFirstPickDraw)  // needs > 250 consecutive rejections
      throw std::runtime_error("theta sampler exhausted its random draws (impossible odds)");
    if (attempt % 2 == 0) {
      block = rng.block(base + draw);
      w_pos = block[0];
      w_accept = block[1];
    } else {
      w_pos = block[2];
      w_accept = block[3];
    }
    ++attempt;
  });
}

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

TrialDraw TrialMoveSampler::draw(const CounterRandom &rng, std::uint64_t trial,
                                 std::uint32_t n_pick) const
{
  const std::uint64_t base = trial * kDrawsPerTrial;
  const RandomBlock main = rng.block(base + kMainDraw);
  TrialDraw out{};
  out.pick = n_pick ? sample_pick(rng, base, main[0], n_pick) : 0u;
  const double d = d_max_ * uniform_open_from_u32(main[1]);
  const double phi = kTwoPi * uniform_from_u32(main[2]);
  const double theta = sample_theta(theta_, rng, base, main[3]);
  // theta <= pi/2 (rounded down) keeps cos(theta) >= 0, so dz <= 0: moves never go up.
  const double d_sin = d * std::sin(theta);
  out.move.dx = d_sin * std::cos(phi);
  out.move.dy = d_sin * std::sin(phi);
  out.move.dz = -d * std::cos(theta);
  return out;
}

TrialMoveSampler::Polar TrialMoveSampler::draw_polar(const CounterRandom &rng,
                                                     std::uint64_t trial) const
{
  const std::uint64_t base = trial * kDrawsPerTrial;
  const RandomBlock main = rng.block(base + kMainDraw);
  Polar out{};
  out.d = d_max_ * uniform_open_from_u32(main[1]);
  out.phi = kTwoPi * uniform_from_u32(main[2]);
  out.theta = sample_theta(theta_, rng, base, main[3]);
  return out;
}

}  // namespace tapmc
