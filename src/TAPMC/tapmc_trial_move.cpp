// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Trial displacement of the redeposition: strip tables of the theta sampler, the full draw.
#include "tapmc_trial_move.h"

#include "tapmc_checks.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tapmc {


ThetaSampler::ThetaSampler(double theta0, ThetaLaw law) : law_(law), theta0_(theta0)
{
  if (!(theta0 > 0.0 && theta0 <= defaults::kThetaWidthMax))
    throw_outside_range("theta0", theta0, defaults::kThetaWidthRange);
  scaled_ = theta0 < kScaledBelow;
  inv_theta0_sq_ = 1.0 / (theta0 * theta0);
  if (law == ThetaLaw::Solid) {
    build_solid();
    return;
  }
  if (law == ThetaLaw::Exponential || law == ThetaLaw::Linear) {
    build_inversion();
    return;
  }
  norm_ = std::erf(kThetaMax / theta0);
  // Equal-probability strip edges: cdf(edge_k) = k / kStrips, by bisection (cdf is strictly
  // increasing). The loop stops at the double resolution of the edge, which takes at most
  // ~1100 halvings of [0, pi/2] (edges near the smallest subnormal for the smallest theta0).
  constexpr int kMaxHalvings = 1200;
  edge_[0] = 0.0;
  edge_[kStrips] = kThetaMax;
  for (int k = 1; k < kStrips; ++k) {
    const double target = static_cast<double>(k) / kStrips;
    double lo = edge_[k - 1], hi = kThetaMax;
    for (int it = 0; it < kMaxHalvings && hi - lo > 0.0; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      if (cdf(mid) < target)
        lo = mid;
      else
        hi = mid;
    }
    edge_[k] = 0.5 * (lo + hi);
  }
  // Per strip, in units of theta0 (x = theta / theta0): the strip holds the mass
  // int_{xl}^{xr} exp(-x^2) dx = (sqrt(pi) / 2) (erf(xr) - erf(xl)); the flat envelope has
  // mass exp(-xl^2) (xr - xl), the exponential one exp(-xl^2) (1 - exp(-2 xl (xr - xl))) / (2 xl).
  // Acceptance = strip mass / envelope mass; exp(xl^2) stays below e^5 (xl is at most the
  // 255/256 quantile of the half-Gaussian, ~2.05).
  for (int k = 0; k < kStrips; ++k) {
    width_[k] = edge_[k + 1] - edge_[k];
    const double l = edge_[k], r = edge_[k + 1];
    squeeze_[k] = std::exp(-flat_exponent(r, l));  // P(right) / P(left)
    const double xl = l / theta0, xw = width_[k] / theta0;
    const double mass_scaled = 0.5 * kSqrtPi * (std::erf(r / theta0) - std::erf(xl)) *
                               std::exp(xl * xl);  // strip mass / exp(-xl^2)
    const double flat_acceptance = xw > 0.0 ? mass_scaled / xw : 1.0;
    rate_[k] = 2.0 * xl;
    span_[k] = -std::expm1(-rate_[k] * xw);  // 1 - exp(-rate xw); 1 when xw is infinite
    const double tail_acceptance = rate_[k] > 0.0 ? mass_scaled * rate_[k] / span_[k] : 0.0;
    tail_[k] = flat_acceptance < defaults::kThetaFlatMinAcceptance && rate_[k] > 0.0 &&
               tail_acceptance > flat_acceptance;
    acceptance_[k] = std::min(1.0, tail_[k] ? tail_acceptance : flat_acceptance);
    first_squeeze_[k] = tail_[k] ? -1.0 : squeeze_[k];  // uniforms lie in (0, 1)
  }
}

namespace {

// 8-point Gauss-Legendre rule on [-1, 1] (nodes +-kGaussNode[k], weights kGaussWeight[k]).
constexpr double kGaussNode[4] = {0.18343464249564978, 0.52553240991632899,
                                  0.79666647741362673, 0.96028985649753618};
constexpr double kGaussWeight[4] = {0.36268378337836177, 0.31370664587788705,
                                    0.22238103445337434, 0.10122853629037669};
// Solid law: beyond x = theta / theta0 = kSolidCut, exp(-x^2) < 1e-695: no mass left.
constexpr double kSolidCut = 40.0;

}  // namespace

double ThetaSampler::solid_sin_over(double x) const
{
  const double t = theta0_ * x;
  if (t < 1e-4) {  // series: the quotient of tiny (or subnormal) values would lose digits
    const double t2 = t * t;
    return x * (1.0 - t2 / 6.0 * (1.0 - t2 / 20.0));
  }
  return std::sin(t) / theta0_;
}

double ThetaSampler::solid_g(double x) const { return std::exp(-x * x) * solid_sin_over(x); }

double ThetaSampler::solid_integral(double x) const
{
  if (x <= 0.0) return 0.0;
  if (x >= x_cut_) return solid_cum_[kSolidPanels];
  const int j = std::min(kSolidPanels - 1, static_cast<int>(x / panel_));
  const double a = j * panel_, half = 0.5 * (x - a), mid = a + half;
  double sum = 0.0;
  for (int k = 0; k < 4; ++k)
    sum += kGaussWeight[k] * (solid_g(mid - half * kGaussNode[k]) + solid_g(mid + half * kGaussNode[k]));
  return solid_cum_[j] + half * sum;
}

// Tables of the solid-angle law (class comment), in units x = theta / theta0.
void ThetaSampler::build_solid()
{
  const double x_top = kThetaMax / theta0_;
  x_cut_ = std::min(x_top, kSolidCut);
  panel_ = x_cut_ / kSolidPanels;
  solid_cum_[0] = 0.0;
  for (int j = 0; j < kSolidPanels; ++j) {
    const double half = 0.5 * panel_, mid = (j + 0.5) * panel_;
    double sum = 0.0;
    for (int k = 0; k < 4; ++k)
      sum += kGaussWeight[k] *
             (solid_g(mid - half * kGaussNode[k]) + solid_g(mid + half * kGaussNode[k]));
    solid_cum_[j + 1] = solid_cum_[j] + half * sum;
  }
  norm_ = solid_cum_[kSolidPanels];
  // the mode: d ln g / dx = cos(theta0 x) / (sin(theta0 x) / theta0) - 2x decreases from +inf
  // to -2 x_top < 0 at pi/2, and is <= 1/x - 2x: the root lies in (0, 1/sqrt(2)]
  double lo = 0.0, hi = std::min(x_top, 1.0);
  for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (std::cos(theta0_ * mid) / solid_sin_over(mid) - 2.0 * mid > 0.0 ? lo : hi) = mid;
  }
  const double x_mode = 0.5 * (lo + hi);
  constexpr int kMaxHalvings = 1200;  // as for the angle law
  edge_[0] = 0.0;
  edge_[kStrips] = kThetaMax;
  for (int k = 1; k < kStrips; ++k) {
    const double target = static_cast<double>(k) / kStrips;
    double a = edge_[k - 1], b = kThetaMax;
    for (int it = 0; it < kMaxHalvings && b - a > 0.0; ++it) {
      const double mid = 0.5 * (a + b);
      if (mid <= a || mid >= b) break;
      (cdf(mid) < target ? a : b) = mid;
    }
    edge_[k] = 0.5 * (a + b);
  }
  for (int k = 0; k < kStrips; ++k) {
    const double l = edge_[k], r = edge_[k + 1];
    width_[k] = r - l;
    const double xl = l / theta0_, xr = r / theta0_, xw = width_[k] / theta0_;
    // log-concave: the maximum on the strip is at the mode or at the edge nearer to it, the
    // minimum at an edge
    const double xp = x_mode < xl ? xl : (x_mode > xr ? xr : x_mode);
    peak_[k] = x_mode < xl ? l : (x_mode > xr ? r : theta0_ * x_mode);
    const double g_peak = solid_g(xp), g_left = solid_g(xl), g_right = solid_g(xr);
    squeeze_[k] = std::min(g_left, g_right) / g_peak;
    const double mass = solid_integral(xr) - solid_integral(xl);
    const double flat_acceptance = xw > 0.0 ? mass / (g_peak * xw) : 1.0;
    // tangent of ln g at the left edge (strips past the mode): slope -rate
    const double cot_term = xl > 0.0 ? std::cos(theta0_ * xl) / solid_sin_over(xl) : 0.0;
    rate_[k] = x_mode < xl ? 2.0 * xl - cot_term : 0.0;
    span_[k] = -std::expm1(-rate_[k] * xw);
    const double tail_acceptance = rate_[k] > 0.0 ? mass * rate_[k] / (g_left * span_[k]) : 0.0;
    tail_[k] = flat_acceptance < defaults::kThetaFlatMinAcceptance && rate_[k] > 0.0 &&
               tail_acceptance > flat_acceptance;
    theta0_cot_left_[k] = cot_term;
    inv_sin_ref_[k] = 1.0 / std::sin(tail_[k] ? l : peak_[k]);
    acceptance_[k] = std::min(1.0, tail_[k] ? tail_acceptance : flat_acceptance);
    first_squeeze_[k] = tail_[k] ? -1.0 : squeeze_[k];
  }
}

// Exponential and Linear: constants of the inverse CDF; no strips (the strip diagnostics read
// as every first attempt accepted without exp).
void ThetaSampler::build_inversion()
{
  by_inversion_ = true;
  if (law_ == ThetaLaw::Exponential) {
    norm_ = -std::expm1(-kThetaMax / theta0_);
  } else {
    support_ = std::min(theta0_, kThetaMax);
    norm_ = theta0_ <= kThetaMax ? 0.5 * theta0_ : support_ * (1.0 - 0.5 * (support_ / theta0_));
  }
  for (int k = 0; k <= kStrips; ++k) edge_[k] = kThetaMax * k / kStrips;
  for (int k = 0; k < kStrips; ++k) {
    width_[k] = edge_[k + 1] - edge_[k];
    squeeze_[k] = first_squeeze_[k] = acceptance_[k] = 1.0;
  }
}

double ThetaSampler::density(double theta) const
{
  if (theta < 0.0 || theta > kThetaMax) return 0.0;
  if (law_ == ThetaLaw::Solid) return solid_g(theta / theta0_) / (theta0_ * norm_);
  if (law_ == ThetaLaw::Exponential) return std::exp(-theta / theta0_) / (theta0_ * norm_);
  if (law_ == ThetaLaw::Linear)
    return theta <= support_ ? (1.0 - theta / theta0_) / norm_ : 0.0;
  // A = 2 / (sqrt(pi) theta0 erf(pi / (2 theta0))) normalises eq. 1 on [0, pi/2].
  const double x = theta / theta0_;
  return 2.0 / (kSqrtPi * theta0_ * norm_) * std::exp(-x * x);
}

double ThetaSampler::cdf(double theta) const
{
  if (theta <= 0.0) return 0.0;
  if (theta >= kThetaMax) return 1.0;
  if (law_ == ThetaLaw::Solid) return solid_integral(theta / theta0_) / norm_;
  if (law_ == ThetaLaw::Exponential) return -std::expm1(-theta / theta0_) / norm_;
  if (law_ == ThetaLaw::Linear)
    return theta >= support_ ? 1.0 : theta * (1.0 - 0.5 * (theta / theta0_)) / norm_;
  return std::erf(theta / theta0_) / norm_;
}

double ThetaSampler::exp_fraction() const
{
  // flat strips: 1 - squeeze; tail strips: P(u > 1 - s^2) <= E[s^2] <= 2 / rate^2 (angle),
  // every point (solid)
  double sum = 0.0;
  for (int k = 0; k < kStrips; ++k)
    sum += tail_[k] ? (law_ == ThetaLaw::Solid ? 1.0 : std::min(1.0, 2.0 / (rate_[k] * rate_[k])))
                    : 1.0 - squeeze_[k];
  return sum / kStrips;
}

double ThetaSampler::min_acceptance() const
{
  return *std::min_element(acceptance_.begin(), acceptance_.end());
}

int ThetaSampler::tail_strips() const
{
  return static_cast<int>(std::count(tail_.begin(), tail_.end(), true));
}

SinCosTable::SinCosTable(double range) : step_(range / kNodes), inv_step_(kNodes / range)
{
  for (int j = 0; j <= kNodes; ++j) {
    node_[j] = j * step_;
    sin_[j] = std::sin(node_[j]);
    cos_[j] = std::cos(node_[j]);
  }
}

TrialMoveSampler::TrialMoveSampler(double d_max, double theta0, ThetaLaw law)
    : d_max_(d_max), theta_(theta0, law), phi_table_(kTwoPi),
      theta_table_(ThetaSampler::kThetaMax)
{
  if (!(d_max > 0.0 && std::isfinite(d_max)))
    throw_outside_range("d_max", d_max, "(0, +inf)");
}

namespace {

// Positions within one trial's slice of the stream.
constexpr std::uint64_t kMainDraw = 0;         // pick, d, phi, theta strip
constexpr std::uint64_t kFirstThetaDraw = 1;   // two (position, accept) pairs per block
constexpr std::uint64_t kFirstPickDraw = 128;  // fresh words for the rare pick rejection
// Pairs of theta words and pick words per round of the slice. A rejection sampler has no
// bound on its draws: after a round is used up, the same positions are read again under the
// keys of the overflow rounds 1, 2, ... (CounterRandom::round), never under the run's own key.
constexpr std::uint64_t kThetaPairsPerRound = 2 * (kFirstPickDraw - kFirstThetaDraw);
constexpr std::uint64_t kPickWordsPerRound = 4 * (TrialMoveSampler::kDrawsPerTrial - kFirstPickDraw);

std::uint32_t sample_pick(const CounterRandom &rng, std::uint64_t trial, std::uint32_t first_word,
                          std::uint32_t n_pick)
{
  std::uint32_t index = 0;
  if (bounded_index(first_word, n_pick, index)) return index;
  for (std::uint64_t k = 0;; ++k)
    if (bounded_index(TrialMoveSampler::pick_word(rng, trial, k), n_pick, index)) return index;
}

}  // namespace

RandomBlock TrialMoveSampler::theta_block(const CounterRandom &rng, std::uint64_t trial,
                                          std::uint64_t attempt)
{
  const std::uint64_t round = attempt / kThetaPairsPerRound;
  const std::uint64_t within = attempt % kThetaPairsPerRound;
  const std::uint64_t position = trial * kDrawsPerTrial + kFirstThetaDraw + within / 2;
  return round == 0 ? rng.block(position) : rng.round(round).block(position);
}

void TrialMoveSampler::theta_words(const CounterRandom &rng, std::uint64_t trial,
                                   std::uint64_t attempt, std::uint32_t &w_pos,
                                   std::uint32_t &w_accept)
{
  const RandomBlock block = theta_block(rng, trial, attempt);
  w_pos = block[attempt % 2 == 0 ? 0 : 2];
  w_accept = block[attempt % 2 == 0 ? 1 : 3];
}

std::uint32_t TrialMoveSampler::pick_word(const CounterRandom &rng, std::uint64_t trial,
                                          std::uint64_t index)
{
  const std::uint64_t round = index / kPickWordsPerRound;
  const std::uint64_t within = index % kPickWordsPerRound;
  const std::uint64_t position = trial * kDrawsPerTrial + kFirstPickDraw + within / 4;
  const RandomBlock block = round == 0 ? rng.block(position) : rng.round(round).block(position);
  return block[within % 4];
}

double TrialMoveSampler::theta_from(const CounterRandom &rng, std::uint64_t trial,
                                    std::uint32_t strip_word, const RandomBlock &theta_first) const
{
  std::uint64_t attempt = 0;
  RandomBlock block = theta_first;
  // Attempts come in pairs per block (a round holds an even number of attempts): a block is
  // drawn once, for the even attempt, and its second pair serves the odd one. The first block
  // comes with the trial's main block.
  return theta_.sample(strip_word, [&](std::uint32_t &w_pos, std::uint32_t &w_accept) {
    const bool even = attempt % 2 == 0;
    if (even && attempt > 0) block = theta_block(rng, trial, attempt);
    w_pos = block[even ? 0 : 2];
    w_accept = block[even ? 1 : 3];
    ++attempt;
  });
}

// d from main[1], phi from main[2], theta given: the displacement of eq. 1.
inline Displacement TrialMoveSampler::displacement(const RandomBlock &main, double theta) const
{
  const double d = d_max_ * uniform_open_from_u32(main[1]);
  // phi = 2 pi main[2] / 2^32 = sector (top 8 bits) + offset (low 24 bits), both exact.
  const int sector = static_cast<int>(main[2] >> 24);
  const double phi_offset = static_cast<double>(main[2] & 0xFFFFFFu) * (kTwoPi * 0x1.0p-32);
  double sin_phi, cos_phi, sin_theta, cos_theta;
  phi_table_.rotate(sector, phi_offset, sin_phi, cos_phi);
  theta_table_.sincos(theta, sin_theta, cos_theta);
  // theta <= pi/2, so cos(theta) >= 0 up to rounding (~1e-17 at pi/2): the clamp keeps
  // dz <= 0 exactly, moves never go up.
  const double d_sin = d * sin_theta;
  return {d_sin * cos_phi, d_sin * sin_phi, -d * std::max(cos_theta, 0.0)};
}

TrialDraw TrialMoveSampler::finish(const CounterRandom &rng, std::uint64_t trial,
                                   std::uint32_t n_pick, const RandomBlock &main,
                                   const RandomBlock &theta_first) const
{
  TrialDraw out{};
  out.pick = n_pick ? sample_pick(rng, trial, main[0], n_pick) : 0u;
  out.move = displacement(main, theta_from(rng, trial, main[3], theta_first));
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
    throw_outside_range("draw_batch count", count, "[0, " + std::to_string(kBatchMax) + "]");
  std::uint64_t trial[kBatchMax];
  for (int k = 0; k < count; ++k) trial[k] = first + k;
  draw_trials(rng, trial, count, n_pick, out);
}

void TrialMoveSampler::draw_trials(const CounterRandom &rng, const std::uint64_t *trial,
                                   int count, std::uint32_t n_pick, TrialDraw *out) const
{
  if (count < 0 || count > kBatchMax)
    throw_outside_range("draw_trials count", count, "[0, " + std::to_string(kBatchMax) + "]");
  std::uint64_t positions[2 * kBatchMax];
  RandomBlock blocks[2 * kBatchMax];
  for (int k = 0; k < count; ++k) {
    const std::uint64_t base = trial[k] * kDrawsPerTrial;
    positions[k] = base + kMainDraw;
    positions[count + k] = base + kFirstThetaDraw;
  }
  rng.blocks(positions, 2 * count, blocks);
  if (theta_.by_inversion())
    draw_lanes<true>(rng, trial, count, n_pick, blocks, out);
  else
    draw_lanes<false>(rng, trial, count, n_pick, blocks, out);
}

template <bool kInversion>
void TrialMoveSampler::draw_lanes(const CounterRandom &rng, const std::uint64_t *trial, int count,
                                  std::uint32_t n_pick, const RandomBlock *blocks,
                                  TrialDraw *out) const
{
  // Lane-parallel pass over the draws that need no rejection step: the pick's first word is
  // accepted, the theta strip is flat and its first point passes the squeeze test (most
  // draws). finish() redoes the others from the same blocks, so every draw is bit-identical to
  // draw().
  // 64-bit lanes throughout, so that a vector holds 8 draws (bytes would make it 64).
  std::uint64_t pick[kBatchMax], slow[kBatchMax];
  double dx[kBatchMax], dy[kBatchMax], dz[kBatchMax];
  for (int k = 0; k < count; ++k) {
    const RandomBlock &main = blocks[k], &theta_first = blocks[count + k];
    const std::uint64_t product = static_cast<std::uint64_t>(main[0]) * n_pick;
    // bounded_index's acceptance without its rare threshold test (left to finish())
    const bool pick_done = static_cast<std::uint32_t>(product) >= n_pick;
    pick[k] = product >> 32;
    double theta;
    bool theta_done = true;
    if constexpr (kInversion)
      theta = theta_.invert(main[3], theta_first[0]);
    else
      theta_done = theta_.first_attempt(main[3], theta_first[0], theta_first[1], theta);
    const Displacement move = displacement(main, theta);
    dx[k] = move.dx;
    dy[k] = move.dy;
    dz[k] = move.dz;
    slow[k] = !(pick_done && theta_done) ? 1u : 0u;
  }
  for (int k = 0; k < count; ++k)
    out[k] = slow[k] ? finish(rng, trial[k], n_pick, blocks[k], blocks[count + k])
                     : TrialDraw{static_cast<std::uint32_t>(pick[k]), {dx[k], dy[k], dz[k]}};
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
