// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The biased trial displacement of the redeposition (paper, section II, eq. 1), drawn exactly
// from counter-based random numbers keyed by (seed, stream, trial).
#ifndef TAPMC_TRIAL_MOVE_H
#define TAPMC_TRIAL_MOVE_H

#include "tapmc_math.h"
#include "tapmc_random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace tapmc {

// The law of theta ('theta_law' of fix mc/settle). The paper (section II) gives
// P(theta) = A exp(-(theta/theta0)^2) without saying per what measure:
//  - Angle (the default): a density in theta, theta has density A exp(-(theta/theta0)^2);
//  - Solid: a density per unit solid angle, so theta has density A' exp(-(theta/theta0)^2)
//    sin(theta) (dOmega = sin(theta) dtheta dphi); very large theta0 then gives directions
//    uniform on the downward hemisphere, where Angle gives theta uniform.
// and says that "a Poissonian and a linear distribution give qualitatively the same
// phenomenology; the pertinent parameter is the width theta0", without their formulas. Read
// with theta0 where eq. 1 has it (the 1/e point of the exponential, the end of the line), both
// densities in theta and truncated at pi/2 as eq. 1:
//  - Exponential: P(theta) = A exp(-theta / theta0);
//  - Linear: P(theta) = A (1 - theta / theta0) on [0, min(theta0, pi/2)], zero beyond.
// phi is uniform under all four.
// The values are stored in restart files (fix mc/settle): never renumber them.
enum class ThetaLaw { Angle = 0, Solid = 1, Exponential = 2, Linear = 3 };

// theta from P(theta) = A exp(-(theta/theta0)^2) on [0, pi/2] (eq. 1; theta from the downward
// vertical), sampled exactly for every theta0 in (0, defaults::kThetaWidthMax] (the strips below
// were designed for theta0 <= pi/2; above it P is flatter still, every strip is flat and accepts
// nearly all its points: min_acceptance() > 0.99 from theta0 = 3 on): [0, pi/2] is cut into kStrips
// strips of equal probability (edges from the inverse of the erf-based CDF, computed once), a
// strip is picked uniformly, and a point of the strip is drawn by rejection from an envelope of
// P on the strip:
//  - flat strips: the constant envelope P(left) (P decreases on [0, pi/2]); a "squeeze" test
//    against the strip's right density accepts most points without evaluating exp;
//  - tail strips (where the flat envelope would accept less than
//    defaults::kThetaFlatMinAcceptance of the points: wide strips of a narrow Gaussian, e.g. the
//    last strip [~2 theta0, pi/2] of theta0 = 0.1): the tangent exponential envelope
//    P(left) exp(-lambda (theta - left)), lambda = 2 left / theta0^2. ln P is concave, so the
//    tangent lies above P everywhere; theta - left is drawn from the truncated exponential by
//    inversion and accepted with probability exp(-((theta - left) / theta0)^2).
// Every strip accepts at least ~3/4 of its proposals (min_acceptance()) for any theta0 above the
// subnormal range.
// The result is exact up to double rounding of the strip edges.
// ThetaLaw::Solid uses the same strips and the same random words per attempt (so the same keying
// and the same lane-parallel first attempt, from its own tables), for the density
// f(theta) ~ exp(-(theta/theta0)^2) sin(theta), which is log-concave (both factors are) with
// its mode inside (0, pi/2): flat strips use the envelope max f on the strip (at the mode or an
// edge) and the squeeze min f (an edge), tail strips (past the mode) the tangent exponential of
// ln f at the left edge, lambda = 2 left / theta0^2 - cot(left). The edges come from the CDF by
// Gauss-Legendre quadrature (no closed form), accurate to ~1e-15. Every strip accepts at least
// ~1/2 of its proposals (the first strip, where f rises from 0 at theta = 0).
// ThetaLaw::Exponential and Linear have closed-form inverse CDFs: theta is the inverse at one
// uniform of 52 bits made of the strip word and the first position word (exact up to double
// rounding; no strips, no rejection, every draw done in its first attempt).
class ThetaSampler {
 public:
  static constexpr int kStrips = 256;
  static constexpr double kThetaMax = 0.5 * kPi;  // exact: halving does not round

  // theta0 in (0, defaults::kThetaWidthMax]; throws std::invalid_argument otherwise.
  explicit ThetaSampler(double theta0, ThetaLaw law = ThetaLaw::Angle);

  double theta0() const { return theta0_; }
  ThetaLaw law() const { return law_; }
  // Exponential and Linear: theta by inversion of the CDF (invert()), not from the strips.
  bool by_inversion() const { return by_inversion_; }

  // Normalised density P(theta) and its CDF on [0, pi/2] (for tests and tools).
  double density(double theta) const;
  double cdf(double theta) const;

  // One exact sample. `strip_word` chooses the strip (its top 8 bits); `next_pair(u0, u1)`
  // supplies fresh independent 32-bit words (position within the strip, acceptance test) as
  // often as the rejection step needs them (on average at most 1 / min_acceptance() pairs).
  // The law is fixed at construction; sample() is only reached by draws whose first attempt
  // was not accepted by the branch-free first_attempt() (the few per cent that need exp).
  template <class NextPair>
  double sample(std::uint32_t strip_word, NextPair &&next_pair) const
  {
    if (by_inversion_) {
      std::uint32_t w_pos, w_accept;
      next_pair(w_pos, w_accept);
      return invert(strip_word, w_pos);
    }
    const unsigned strip = strip_word >> 24;
    if (law_ == ThetaLaw::Solid) {
      // f / envelope = exp(-s^2 - theta0 s cot(left)) sin(theta) / sin(left) on a tail strip,
      // f(theta) / f(peak) on a flat one (see the class comment)
      return sample_strips(
          strip, next_pair,
          [&](double s, double theta, double u) {
            return u <= std::exp(-s * (s + theta0_cot_left_[strip])) * sin_ratio(theta, strip);
          },
          [&](double theta, double u) {
            const double p = peak_[strip];
            return u <= std::exp(-((theta - p) / theta0_) * ((theta + p) / theta0_)) *
                            sin_ratio(theta, strip);
          });
    }
    const double left = edge_[strip];
    return sample_strips(
        strip, next_pair,
        [](double s, double, double u) {
          const double s2 = s * s;
          return u <= 1.0 - s2 || u <= std::exp(-s2);  // exp(-s^2) >= 1 - s^2: often no exp
        },
        [&](double theta, double u) { return u <= std::exp(-flat_exponent(theta, left)); });
  }

  // The first attempt of sample() when it is the last: a flat strip whose squeeze test accepts
  // the point, which is most draws. Returns false where sample() would go on (a tail strip, or
  // a point the squeeze test does not accept; theta is then meaningless). The same arithmetic
  // as sample() and no branch, so that a batch of draws runs lane-parallel.
  bool first_attempt(std::uint32_t strip_word, std::uint32_t w_pos, std::uint32_t w_accept,
                     double &theta) const
  {
    const unsigned strip = strip_word >> 24;
    theta = std::min(edge_[strip] + width_[strip] * uniform_open_from_u32(w_pos), kThetaMax);
    return uniform_open_from_u32(w_accept) <= first_squeeze_[strip];
  }

  // Exponential and Linear: the inverse of the CDF at u = (the 52 top bits of high, low, read
  // as one integer + 1/2) / 2^52, in (0, 1).
  double invert(std::uint32_t high, std::uint32_t low) const
  {
    const std::uint64_t bits = (static_cast<std::uint64_t>(high) << 20) | (low >> 12);
    const double u = (static_cast<double>(bits) + 0.5) * 0x1.0p-52;
    const double mass = u * norm_;
    if (law_ == ThetaLaw::Exponential)  // 1 - exp(-theta / theta0) = mass
      return std::min(-theta0_ * std::log1p(-mass), kThetaMax);
    // theta - theta^2 / (2 theta0) = mass, the root without cancellation
    return std::min(2.0 * mass / (1.0 + std::sqrt(std::max(0.0, 1.0 - 2.0 * mass / theta0_))),
                    support_);
  }

  // Fraction of first attempts that need exp (diagnostic of the squeeze efficiency).
  double exp_fraction() const;
  // Smallest acceptance probability of a proposal over the strips (exact, from the CDF).
  double min_acceptance() const;
  // Number of strips sampled from the exponential envelope.
  int tail_strips() const;

 private:
  // The rejection step on the strips, shared by Angle and Solid. A tail strip proposes
  // theta = left + theta0 s with s ~ truncated Exp(rate) on [0, width / theta0] (inversion), a
  // flat strip a uniform point; a flat proposal below the strip's squeeze is accepted at once,
  // the others by the law's test: accept_tail(s, theta, u), accept_flat(theta, u).
  template <class NextPair, class AcceptTail, class AcceptFlat>
  double sample_strips(unsigned strip, NextPair &next_pair, AcceptTail &&accept_tail,
                       AcceptFlat &&accept_flat) const
  {
    const double left = edge_[strip];
    std::uint32_t w_pos, w_accept;
    if (tail_[strip]) {
      const double rate = rate_[strip], span = span_[strip];
      const double right = std::min(edge_[strip + 1], kThetaMax);
      for (;;) {
        next_pair(w_pos, w_accept);
        const double s = -std::log1p(-span * uniform_open_from_u32(w_pos)) / rate;
        const double theta = std::min(left + theta0_ * s, right);
        if (accept_tail(s, theta, uniform_open_from_u32(w_accept))) return theta;
      }
    }
    const double width = width_[strip];
    for (;;) {
      next_pair(w_pos, w_accept);
      // min(): rounding must never push theta past pi/2 (then cos < 0 and the move would go up)
      const double theta = std::min(left + width * uniform_open_from_u32(w_pos), kThetaMax);
      const double u = uniform_open_from_u32(w_accept);
      if (u <= squeeze_[strip]) return theta;  // below the strip's lowest density: accept
      if (accept_flat(theta, u)) return theta;
    }
  }

  // ln(P(left) / P(theta)) = (theta - left)(theta + left) / theta0^2. Below
  // kScaledBelow, 1 / theta0^2 would overflow: the factors are scaled by theta0 first.
  static constexpr double kScaledBelow = 1e-100;
  double flat_exponent(double theta, double left) const
  {
    if (scaled_) return ((theta - left) / theta0_) * ((theta + left) / theta0_);
    return (theta - left) * (theta + left) * inv_theta0_sq_;
  }

  // sin(theta) / sin(reference of the strip: its peak (flat) or left edge (tail)), Solid only.
  double sin_ratio(double theta, unsigned strip) const
  {
    return std::sin(theta) * inv_sin_ref_[strip];
  }
  // ThetaLaw::Solid, in units x = theta / theta0: g(x) = exp(-x^2) sin(theta0 x) / theta0 (the
  // density up to a constant, finite for every theta0), its integral from 0 by composite
  // Gauss-Legendre quadrature, and the strip tables.
  double solid_sin_over(double x) const;
  double solid_g(double x) const;
  double solid_integral(double x) const;  // int_0^x g
  void build_solid();
  void build_inversion();

  ThetaLaw law_;
  bool by_inversion_ = false;
  // norm_: the law's unnormalised CDF at the truncation (erf(pi/2 / theta0); the solid
  // quadrature's total; 1 - exp(-pi/2 / theta0); b - b^2 / (2 theta0)); support_: the end of
  // the support, b = min(theta0, pi/2) for Linear, pi/2 otherwise
  double support_ = kThetaMax;
  double theta0_, inv_theta0_sq_, norm_;
  bool scaled_;
  // Solid: panels of the quadrature on [0, x_cut_], cumulative integrals at their edges
  static constexpr int kSolidPanels = 1024;
  double x_cut_ = 0.0, panel_ = 0.0;
  std::array<double, kSolidPanels + 1> solid_cum_{};
  std::array<double, kStrips> peak_{}, inv_sin_ref_{}, theta0_cot_left_{};
  std::array<double, kStrips + 1> edge_{};
  std::array<double, kStrips> width_{}, squeeze_{}, rate_{}, span_{}, acceptance_{};
  std::array<double, kStrips> first_squeeze_{};  // squeeze_ of flat strips, -1 for tail strips
  std::array<bool, kStrips> tail_{};
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

  // d_max > 0 and finite, theta0 in (0, defaults::kThetaWidthMax]; throws
  // std::invalid_argument otherwise.
  TrialMoveSampler(double d_max, double theta0, ThetaLaw law = ThetaLaw::Angle);

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

  // Trials trial[0 .. count) (any numbers, count <= kBatchMax) at once, bit-identical to draw().
  void draw_trials(const CounterRandom &rng, const std::uint64_t *trial, int count,
                   std::uint32_t n_pick, TrialDraw *out) const;

  // The random words behind a draw's rejection steps, from positions of the trial's slice and,
  // past the slice, of the overflow rounds (never exhausted): the pair of theta attempt
  // `attempt` (attempts 0 and 1 share the first theta block), and extra pick word `index`.
  static void theta_words(const CounterRandom &rng, std::uint64_t trial, std::uint64_t attempt,
                          std::uint32_t &w_pos, std::uint32_t &w_accept);
  // The block holding the words of theta attempt `attempt` (and of its pair partner).
  static RandomBlock theta_block(const CounterRandom &rng, std::uint64_t trial,
                                 std::uint64_t attempt);
  static std::uint32_t pick_word(const CounterRandom &rng, std::uint64_t trial,
                                 std::uint64_t index);

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
  // draw_trials after its random blocks: the lane-parallel pass and the rest, for one way of
  // drawing theta's first attempt (strips, or inversion), chosen once per batch.
  template <bool kInversion>
  void draw_lanes(const CounterRandom &rng, const std::uint64_t *trial, int count,
                  std::uint32_t n_pick, const RandomBlock *blocks, TrialDraw *out) const;
  Displacement displacement(const RandomBlock &main, double theta) const;

  double d_max_;
  ThetaSampler theta_;
  SinCosTable phi_table_, theta_table_;
};

}  // namespace tapmc

#endif
