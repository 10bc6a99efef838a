// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The biased trial displacement of the redeposition (paper, section II, eq. 1), drawn exactly
// from counter-based random numbers keyed by (seed, stream, trial).
#ifndef TAPMC_TRIAL_MOVE_H
#define TAPMC_TRIAL_MOVE_H

#include "tapmc_random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace tapmc {

// theta from P(theta) = A exp(-(theta/theta0)^2) on [0, pi/2] (eq. 1; theta from the downward
// vertical), sampled exactly and cheaply: [0, pi/2] is cut into kStrips strips of equal
// probability (edges from the inverse of the erf-based CDF, computed once), a strip is picked
// uniformly, and a point of the strip is drawn by rejection from the flat envelope at the
// strip's left (highest) density. Since P decreases on [0, pi/2], a "squeeze" test against the
// strip's right density accepts most points without evaluating exp. The result is exact up to
// double rounding of the strip edges.
class ThetaSampler {
 public:
  static constexpr int kStrips = 256;
  static constexpr double kThetaMax = 1.57079632679489661923;  // pi/2

  // theta0 in (0, pi/2]; throws std::invalid_argument otherwise.
  explicit ThetaSampler(double theta0);

  double theta0() const { return theta0_; }

  // Normalised density P(theta) and its CDF on [0, pi/2] (for tests and tools).
  double density(double theta) const;
  double cdf(double theta) const;

  // One exact sample. `strip_word` chooses the strip (its top 8 bits); `next_pair(u0, u1)`
  // supplies fresh independent 32-bit words (position within the strip, acceptance test) as
  // often as the rejection step needs them (on average 1.0x pairs; see reject_fraction()).
  template <class NextPair>
  double sample(std::uint32_t strip_word, NextPair &&next_pair) const
  {
    const unsigned strip = strip_word >> 24;
    const double left = edge_[strip];
    const double width = width_[strip];
    for (;;) {
      std::uint32_t w_pos, w_accept;
      next_pair(w_pos, w_accept);
      // min(): rounding must never push theta past pi/2 (then cos < 0 and the move would go up)
      const double theta = std::min(left + width * uniform_open_from_u32(w_pos), kThetaMax);
      const double u = uniform_open_from_u32(w_accept);
      if (u <= squeeze_[strip]) return theta;  // below the strip's lowest density: accept
      // P(theta) / P(left) = exp(-(theta - left)(theta + left) / theta0^2)
      if (u <= std::exp(-(theta - left) * (theta + left) * inv_theta0_sq_)) return theta;
    }
  }

  // Fraction of first attempts that need exp (diagnostic of the squeeze efficiency).
  double exp_fraction() const;

 private:
  double theta0_, inv_theta0_sq_, norm_;
  std::array<double, kStrips + 1> edge_{};
  std::array<double, kStrips> width_{}, squeeze_{};
};

// sin and cos of angles in a fixed range [0, range] from a table of 256 nodes and short
// Taylor series in the offset from the nearest lower node (|offset| <= range / 256; with
// range <= 2 pi the truncation error is below 1e-20, so results are correct to a few ulp),
// several times cheaper than std::sin + std::cos.
class SinCosTable {
 public:
  static constexpr int kNodes = 256;
  explicit SinCosTable(double range);
  void sincos(double angle, double &sin_out, double &cos_out) const
  {
    int j = static_cast<int>(angle * inv_step_);
    j = j < 0 ? 0 : (j > kNodes ? kNodes : j);
    rotate(j, angle - node_[j], sin_out, cos_out);
  }
  // Node j plus offset delta: sin/cos by the angle-addition formula.
  void rotate(int j, double delta, double &sin_out, double &cos_out) const
  {
    const double d2 = delta * delta;
    // sin(d) = d (1 - d^2/6 + d^4/120 - d^6/5040); cos(d) = 1 - d^2/2 + d^4/24 - d^6/720 + d^8/40320
    const double sin_d = delta * (1.0 + d2 * (-1.0 / 6 + d2 * (1.0 / 120 + d2 * (-1.0 / 5040))));
    const double cos_d =
        1.0 + d2 * (-0.5 + d2 * (1.0 / 24 + d2 * (-1.0 / 720 + d2 * (1.0 / 40320))));
    sin_out = sin_[j] * cos_d + cos_[j] * sin_d;
    cos_out = cos_[j] * cos_d - sin_[j] * sin_d;
  }
  double step() const { return step_; }

 private:
  double step_, inv_step_;
  std::array<double, kNodes + 1> node_{}, sin_{}, cos_{};
};

struct Displacement {
  double dx, dy, dz;
};

// Everything a trial needs, drawn from the positions of one trial in the random stream.
struct TrialDraw {
  std::uint32_t pick;  // index in [0, n_pick) (0 when n_pick == 0)
  Displacement move;
};

// The trial displacement: d uniform in [0, d_max], phi uniform in [0, 2 pi), theta ~ eq. 1,
// dx = d sin(theta) cos(phi), dy = d sin(theta) sin(phi), dz = -d cos(theta) <= 0.
// Random positions used by trial t: t * kDrawsPerTrial + k (k < kDrawsPerTrial), so every
// trial's numbers depend on (seed, stream, t) only.
class TrialMoveSampler {
 public:
  static constexpr std::uint64_t kDrawsPerTrial = 256;

  // d_max > 0 and finite, theta0 in (0, pi/2]; throws std::invalid_argument otherwise.
  TrialMoveSampler(double d_max, double theta0);

  double d_max() const { return d_max_; }
  const ThetaSampler &theta_sampler() const { return theta_; }

  // Trial `trial` of the stream: a uniform pick in [0, n_pick) (skipped if n_pick == 0) and
  // the displacement.
  TrialDraw draw(const CounterRandom &rng, std::uint64_t trial, std::uint32_t n_pick) const;

  // Trials first .. first + count - 1 at once (count <= kBatchMax), bit-identical to draw():
  // the random blocks of all trials are computed lane-parallel.
  static constexpr int kBatchMax = CounterRandom::kBatchMax / 2;
  void draw_batch(const CounterRandom &rng, std::uint64_t first, int count, std::uint32_t n_pick,
                  TrialDraw *out) const;

  // The angles and length of the same draw (for tests of the distributions).
  struct Polar {
    double d, theta, phi;
  };
  Polar draw_polar(const CounterRandom &rng, std::uint64_t trial) const;

 private:
  // The draw from its two always-used random blocks (main: pick, d, phi, strip; theta_first:
  // the first two position/acceptance pairs of the theta rejection step).
  TrialDraw finish(const CounterRandom &rng, std::uint64_t trial, std::uint32_t n_pick,
                   const RandomBlock &main, const RandomBlock &theta_first) const;
  double theta_from(const CounterRandom &rng, std::uint64_t trial, std::uint32_t strip_word,
                    const RandomBlock &theta_first) const;

  double d_max_;
  ThetaSampler theta_;
  SinCosTable phi_table_, theta_table_;
};

}  // namespace tapmc

#endif
