// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Pore statistics: where the packing is (floor, free surface, walls), the selection, histograms,
// nu, Gotoh's P0 measured and in Percus-Yevick form.
#include "tapmc_pores/analysis.h"
#include "tapmc_pores/errors.h"

#include "tapmc_math.h"
#include "tapmc_random.h"
#include "tapmc_stereology.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace tapmc {
namespace pores {
double surface_height(const std::vector<double>& xyz, double radius, const std::array<double, 2>& lo,
                      const std::array<double, 2>& hi, double column_width) {
  if (!(column_width > 0)) throw std::invalid_argument("surface column width must be > 0, got " + message_number(column_width));
  // The columns of compute stereo/profile (make_column_grid: the count forgives the last digits
  // of L / width, at most kMaxColumnsPerAxis a side), clamped at the faces of the extent.
  stereo::Box extent;
  for (int d = 0; d < 2; ++d) {
    extent.lo[d] = lo[d];
    extent.hi[d] = hi[d] > lo[d] ? hi[d] : lo[d] + column_width;
    extent.periodic[d] = false;
  }
  const stereo::ColumnGrid grid = stereo::make_column_grid(extent, column_width, true);
  std::vector<double> tops(static_cast<std::size_t>(grid.size()), -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; 3 * i < xyz.size(); ++i) {
    double& top = tops[static_cast<std::size_t>(grid.column_of(xyz[3 * i], xyz[3 * i + 1]))];
    top = std::max(top, xyz[3 * i + 2] + radius);
  }
  return stereo::surface_height(tops.data(), grid.size(), std::numeric_limits<double>::quiet_NaN());
}

PackingBounds find_packing(const Box& box, const std::vector<double>& xyz, double radius, double floor,
                           double column_width_over_radius) {
  if (xyz.empty()) throw std::invalid_argument("no spheres: the packing has no extent");
  PackingBounds packing;
  packing.lo = box.lo;
  packing.hi = box.hi;
  std::array<double, 3> lowest, highest;
  lowest.fill(std::numeric_limits<double>::infinity());
  highest.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; 3 * i < xyz.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      lowest[d] = std::min(lowest[d], xyz[3 * i + d] - radius);
      highest[d] = std::max(highest[d], xyz[3 * i + d] + radius);
    }
  for (int d = 0; d < 2; ++d)
    if (!box.periodic[d]) packing.lo[d] = lowest[d], packing.hi[d] = highest[d];
  packing.lowest_bottom = lowest[2];
  if (box.periodic[2]) {
    if (!std::isnan(floor))
      throw std::invalid_argument("--floor " + message_number(floor) +
                                  " needs a non-periodic z, but z is periodic (no floor, no free surface)");
    return packing;
  }
  packing.free_surface = true;
  packing.lo[2] = std::isnan(floor) ? lowest[2] : floor;
  packing.hi[2] = surface_height(xyz, radius, {packing.lo[0], packing.lo[1]}, {packing.hi[0], packing.hi[1]},
                                 column_width_over_radius * radius);
  if (!(packing.hi[2] > packing.lo[2])) {
    std::ostringstream what;
    what << "--floor " << packing.lo[2] << " is not below the free surface h_s = " << packing.hi[2]
         << " (lowest sphere bottom " << lowest[2] << ")";
    throw std::invalid_argument(what.str());
  }
  return packing;
}

double Region::volume() const {
  const double base = disk ? kPi * disk_radius * disk_radius : (hi[0] - lo[0]) * (hi[1] - lo[1]);
  return base * (hi[2] - lo[2]);
}

namespace {
// x and y of the selection in a tube: the disk RC - wall_gap R about the axis (the side-wall
// rule, measured radially from the tube's wall), its bounding square in lo/hi.
void set_disk(Region& region, const Box& box, double radius, const RegionSpec& spec) {
  const RegionSpec::Cylinder& tube = spec.cylinder;
  const std::string option = "--cylinder " + tube.text;
  for (int d = 0; d < 2; ++d)
    if (box.periodic[d])
      throw std::invalid_argument(option + ": a tube needs non-periodic x and y, but the dump's " + "xy"[d] +
                                  " is periodic (a tube's walls are not: check the dump's BOX BOUNDS flags, or --boundary)");
  const std::array<double, 2> centre{tube.centre_x, tube.centre_y};
  for (int d = 0; d < 2; ++d) {
    const double slack = config::kBoxTolerance * (box.hi[d] - box.lo[d]);
    if (centre[d] - tube.radius < box.lo[d] - slack || centre[d] + tube.radius > box.hi[d] + slack) {
      std::ostringstream what;
      what << option << ": the tube spans " << "xy"[d] << " in [" << centre[d] - tube.radius << ", "
           << centre[d] + tube.radius << "], outside the box [" << box.lo[d] << ", " << box.hi[d]
           << "]; with RC = " << tube.radius << ", C" << "XY"[d] << " must lie in [" << box.lo[d] + tube.radius << ", "
           << box.hi[d] - tube.radius << "] (RC at most half the box, " << 0.5 * (box.hi[d] - box.lo[d]) << ")";
      throw std::invalid_argument(what.str());
    }
  }
  const double margin = spec.wall_gap_over_radius * radius;
  if (!(tube.radius - margin > 0)) {
    std::ostringstream what;
    what << option << ": empty selection, the radius RC = " << tube.radius << " is not more than the --wall-gap "
         << spec.wall_gap_over_radius << " R = " << margin << " kept from the tube wall (R = " << radius << ")";
    throw std::invalid_argument(what.str());
  }
  region.disk = true;
  region.centre_x = centre[0];
  region.centre_y = centre[1];
  region.disk_radius = tube.radius - margin;
  for (int d = 0; d < 2; ++d) region.lo[d] = centre[d] - region.disk_radius, region.hi[d] = centre[d] + region.disk_radius;
}
}  // namespace

Region make_region(const Box& box, const PackingBounds& packing, double radius, const RegionSpec& spec) {
  Region region;
  if (spec.cylinder.given) set_disk(region, box, radius, spec);
  for (int d = spec.cylinder.given ? 2 : 0; d < 3; ++d) {
    const double gap_lo = box.periodic[d] ? 0.0 : spec.wall_gap_over_radius * radius;
    const double gap_hi = box.periodic[d] ? 0.0
                          : (d == 2 && packing.free_surface ? spec.surface_gap_over_radius : spec.wall_gap_over_radius) * radius;
    auto resolve = [&](double value, double fallback) {
      if (std::isnan(value)) return fallback;
      return spec.units[d] == RegionSpec::Units::kRadiiFromLo ? packing.lo[d] + value * radius : value;
    };
    region.lo[d] = std::max(box.lo[d], resolve(spec.lo[d], packing.lo[d] + gap_lo));
    region.hi[d] = std::min(box.hi[d], resolve(spec.hi[d], packing.hi[d] - gap_hi));
    if (!(region.hi[d] > region.lo[d])) {
      std::ostringstream what;
      what << "empty selection region along " << "xyz"[d] << ": [" << region.lo[d] << ", " << region.hi[d]
           << ") in the box [" << box.lo[d] << ", " << box.hi[d] << "]";
      if (!box.periodic[d]) {
        if (d == 2 && packing.free_surface)
          what << "; the packing spans the floor " << packing.lo[d] << " to the free surface h_s = " << packing.hi[d]
               << ", the defaults keep " << spec.wall_gap_over_radius << " R above the floor (--wall-gap) and "
               << spec.surface_gap_over_radius << " R below h_s (--surface-gap)";
        else
          what << "; the spheres span [" << packing.lo[d] << ", " << packing.hi[d] << "], the defaults keep "
               << spec.wall_gap_over_radius << " R from them (--wall-gap)";
      }
      what << "; R = " << radius << " (give the bounds with --" << "xyz"[d] << " or smaller gaps)";
      throw std::invalid_argument(what.str());
    }
  }
  return region;
}

Histogram::Histogram(double lo, double hi, std::size_t bins) : lo_(lo), hi_(hi), counts_(bins, 0), sums_(bins, 0.0) {
  if (bins == 0) throw std::invalid_argument("histogram needs at least one bin");
  if (!(hi > lo)) throw std::invalid_argument("histogram range must have hi > lo, got [" + message_number(lo) + ", " + message_number(hi) + ")");
}

void Histogram::add(double value) {
  ++total_;
  if (value < lo_) { ++underflow_; return; }
  const double t = (value - lo_) / width();
  if (!(t < static_cast<double>(counts_.size()))) { ++overflow_; return; }
  const auto bin = static_cast<std::size_t>(t);
  ++counts_[bin];
  sums_[bin] += value;
}

void Histogram::merge(const Histogram& other) {
  if (other.counts_.size() != counts_.size() || other.lo_ != lo_ || other.hi_ != hi_)
    throw std::invalid_argument("cannot merge histograms with different bins");
  for (std::size_t i = 0; i < counts_.size(); ++i) {
    counts_[i] += other.counts_[i];
    sums_[i] += other.sums_[i];
  }
  underflow_ += other.underflow_;
  overflow_ += other.overflow_;
  total_ += other.total_;
}

double Histogram::density(std::size_t i) const {
  if (total_ == 0) return 0.0;
  return static_cast<double>(counts_[i]) / (static_cast<double>(total_) * width());
}

double Histogram::weighted_density(std::size_t i) const {
  if (total_ == 0) return 0.0;
  return sums_[i] / (static_cast<double>(total_) * width());
}

PoreStatistics::PoreStatistics(const HistogramSpec& spec)
    : xi(0.0, spec.xi_max, spec.bins), v(0.0, spec.xi_max * spec.xi_max * spec.xi_max, spec.bins) {}

void PoreStatistics::add(const Pore& pore) {
  ++pores;
  if (pore.tetrahedra > 1) ++degenerate;
  const double xi3 = pore.xi * pore.xi * pore.xi;
  sum_xi += pore.xi;
  sum_xi3 += xi3;
  xi.add(pore.xi);
  v.add(xi3);
}

void PoreStatistics::merge(const PoreStatistics& other) {
  pores += other.pores;
  degenerate += other.degenerate;
  sum_xi += other.sum_xi;
  sum_xi3 += other.sum_xi3;
  xi.merge(other.xi);
  v.merge(other.v);
}

double PoreStatistics::nu() const {
  return pores ? sum_xi3 / static_cast<double>(pores) : std::numeric_limits<double>::quiet_NaN();
}
double PoreStatistics::mean_xi() const {
  return pores ? sum_xi / static_cast<double>(pores) : std::numeric_limits<double>::quiet_NaN();
}

double gotoh_p0(double sigma, double phi) {
  if (!(phi > 0 && phi < 1)) throw std::invalid_argument("gotoh_p0: phi must be in (0, 1), got " + message_number(phi));
  if (!(sigma >= 0)) throw std::invalid_argument("gotoh_p0: sigma must be >= 0, got " + message_number(sigma));
  if (sigma <= 1.0) return 1.0 - phi * sigma * sigma * sigma;  // eq. 8: disjoint balls
  // sigma >= 1: the scaled-particle / Percus-Yevick result, in place of the printed eq. 9 (which
  // does not meet eq. 8 at sigma = 1; doc/tapmc-pores.rst). -ln P0 is the cubic in t = sigma - 1
  // that continues eq. 8 with its value and first two derivatives at sigma = 1 and has the
  // PY-compressibility pressure (1 + phi + phi^2) / (1 - phi)^3 as cubic coefficient.
  const double t = sigma - 1.0, q = 1.0 - phi;
  const double exponent = phi / (q * q * q) *
                          (3.0 * q * q * t + q * (3.0 + 1.5 * phi) * t * t + (1.0 + phi + phi * phi) * t * t * t);
  return q * std::exp(-exponent);
}

P0Statistics::P0Statistics(double sigma_max_in, std::size_t steps) : sigma_max(sigma_max_in), farther(steps, 0) {
  if (steps < 2) throw std::invalid_argument("P0 needs at least 2 sigma steps, got " + std::to_string(steps));
  if (!(sigma_max > 1.0)) throw std::invalid_argument("P0 sigma_max must exceed 1, got " + message_number(sigma_max));
}

void P0Statistics::add_distance(double distance_over_radius) {
  ++samples;
  if (distance_over_radius < 1.0) ++inside;
  // farther[k] counts distance > sigma_k: every k with sigma_k < distance.
  const double step = sigma_max / static_cast<double>(steps() - 1);
  const double position = distance_over_radius / step;
  std::size_t below = position <= 0 ? 0 : static_cast<std::size_t>(std::ceil(position));  // sigma_k < d  <=>  k < d/step
  below = std::min(below, steps());
  for (std::size_t k = 0; k < below; ++k) ++farther[k];
}

void P0Statistics::merge(const P0Statistics& other) {
  if (other.steps() != steps() || other.sigma_max != sigma_max) throw std::invalid_argument("cannot merge P0 with different sigma grids");
  for (std::size_t k = 0; k < steps(); ++k) farther[k] += other.farther[k];
  samples += other.samples;
  inside += other.inside;
}

double P0Statistics::p0(std::size_t k) const {
  return samples ? static_cast<double>(farther[k]) / static_cast<double>(samples) : std::numeric_limits<double>::quiet_NaN();
}

double P0Statistics::phi() const {
  return samples ? static_cast<double>(inside) / static_cast<double>(samples) : std::numeric_limits<double>::quiet_NaN();
}

// Point i takes x, y from block 2i and z from block 2i + 1 of the stream (53-bit uniforms).
std::vector<double> random_points(const Region& region, std::size_t count, std::uint64_t seed, std::uint64_t stream) {
  const CounterRandom draws(seed, RandomPurpose::kPoreSamplePoints, stream);
  std::vector<double> points(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const RandomBlock xy = draws.block(2 * static_cast<std::uint64_t>(i));
    const double u[3] = {uniform_from_u64(join_u32(xy[0], xy[1])), uniform_from_u64(join_u32(xy[2], xy[3])),
                         draws.uniform(2 * static_cast<std::uint64_t>(i) + 1)};
    for (int d = 0; d < 3; ++d) points[3 * i + d] = region.lo[d] + u[d] * (region.hi[d] - region.lo[d]);
    if (region.disk) {  // uniform in the disk: area up to distance s grows as s^2
      const double s = region.disk_radius * std::sqrt(u[0]), angle = kTwoPi * u[1];
      points[3 * i] = region.centre_x + s * std::cos(angle);
      points[3 * i + 1] = region.centre_y + s * std::sin(angle);
    }
  }
  return points;
}

RadiusCheck common_radius(const Frame& frame, double fallback, double tolerance) {
  RadiusCheck check;
  if (frame.radius.empty()) {
    if (!(fallback > 0))
      throw RadiusError("the dump has no radius or diameter column: give the sphere radius with --radius", 0);
    check.radius = fallback;
    return check;
  }
  const auto [min_it, max_it] = std::minmax_element(frame.radius.begin(), frame.radius.end());
  check.index_min = static_cast<std::size_t>(min_it - frame.radius.begin());
  check.index_max = static_cast<std::size_t>(max_it - frame.radius.begin());
  const double mean = 0.5 * (*min_it + *max_it);
  std::ostringstream what;
  what.precision(10);
  if (*max_it - *min_it > tolerance * mean) {
    what << "polydisperse input: radii from " << *min_it << " (atom " << frame.ids[check.index_min] << ") to "
         << *max_it << " (atom " << frame.ids[check.index_max]
         << "); the tangent-sphere pore (xi = r/R) is defined for equal spheres only";
    throw RadiusError(what.str(), check.index_max);
  }
  check.radius = mean;
  if (fallback > 0 && std::abs(fallback - mean) > tolerance * mean) {
    what << "--radius " << fallback << " disagrees with the dump's radii (" << mean
         << ", from its radius or diameter column)";
    throw RadiusError(what.str(), 0);
  }
  return check;
}

}  // namespace pores
}  // namespace tapmc
