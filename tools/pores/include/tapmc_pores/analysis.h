// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Pore statistics (CGAL-free): where the packing is, the selection, P(xi), xi^3 P(xi), the number
// density n_v(v) and the volume distribution rho_v(v) of v = xi^3, nu, Gotoh's P0.
#ifndef TAPMC_PORES_ANALYSIS_H
#define TAPMC_PORES_ANALYSIS_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tapmc_pores/dump_reader.h"
#include "tapmc_pores/pores_config.h"
#include "tapmc_pores/tessellation.h"

namespace tapmc {
namespace pores {

// Selection sub-box (pores are selected by the position of their centre). With a tube
// (--cylinder), also the disk of radius disk_radius about (centre_x, centre_y): lo and hi then
// bound that disk in x and y, and the selection is the upright cylinder between lo[2] and hi[2].
struct Region {
  std::array<double, 3> lo{}, hi{};
  bool disk = false;
  double centre_x = 0.0, centre_y = 0.0, disk_radius = 0.0;
  bool contains(const std::array<double, 3>& p) const {
    if (!(p[0] >= lo[0] && p[0] < hi[0] && p[1] >= lo[1] && p[1] < hi[1] && p[2] >= lo[2] && p[2] < hi[2]))
      return false;
    const double dx = p[0] - centre_x, dy = p[1] - centre_y;
    return !disk || dx * dx + dy * dy < disk_radius * disk_radius;
  }
  double volume() const;
};

// Where the packing is, found from the frame's data (z is the vertical; doc/tapmc-pores.rst,
// "Selection"). These are the reference faces of the selection:
//  * periodic directions: the box faces;
//  * non-periodic x or y: the side walls, taken where the outermost spheres are, min x_i - R and
//    max x_i + R (the box may be wider than the walls);
//  * non-periodic z: the floor (given, or the lowest sphere bottom min z_i - R) and the free
//    surface h_s (surface_height()).
struct PackingBounds {
  std::array<double, 3> lo{}, hi{};
  bool free_surface = false;   // z is not periodic: lo[2] is the floor, hi[2] the surface h_s
  double lowest_bottom = 0.0;  // min z_i - R (to check a given floor against)
};

// Mean over columns `column_width` wide tiling [lo, hi) in x and y (n = max(1, floor(L / width))
// per direction, at most kMaxColumnsPerAxis: tapmc::make_column_grid) of the highest sphere top
// z_i + radius in the column; empty columns skipped. The surface height of compute
// stereo/profile, computed by its kernel (doc/compute_stereo_profile.rst).
double surface_height(const std::vector<double>& xyz, double radius, const std::array<double, 2>& lo,
                      const std::array<double, 2>& hi, double column_width);

// `floor`: NaN for the default (the lowest sphere bottom). Throws std::invalid_argument when a
// floor is given for a periodic z or lies at or above the surface.
PackingBounds find_packing(const Box& box, const std::vector<double>& xyz, double radius,
                           double floor = std::numeric_limits<double>::quiet_NaN(),
                           double column_width_over_radius = config::kSurfaceColumnWidth);

// How the user asked for the sub-box; a NaN bound means "default for that side": the reference
// face (PackingBounds) moved inwards by wall_gap R (side walls, floor) or surface_gap R (free
// surface); periodic directions are used whole.
struct RegionSpec {
  enum class Units { kAbsolute, kRadiiFromLo };  // coordinates, or multiples of R above the lower
                                                 // reference face (the floor along z)
  std::array<double, 3> lo{{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::quiet_NaN()}};
  std::array<double, 3> hi = lo;
  std::array<Units, 3> units{{Units::kAbsolute, Units::kAbsolute, Units::kAbsolute}};
  double wall_gap_over_radius = config::kDefaultWallGap;
  double surface_gap_over_radius = config::kDefaultSurfaceGap;
  // A vertical tube (--cylinder CX:CY:RC, box coordinates): x and y of the selection are the disk
  // of radius RC - wall_gap R about (CX, CY), the side-wall rule measured radially from the tube.
  struct Cylinder {
    bool given = false;
    double centre_x = 0.0, centre_y = 0.0, radius = 0.0;
    std::string text;  // as given, for messages
  } cylinder;
};

// The sub-box, clipped to the box. Throws std::invalid_argument if it is empty, or, with a
// cylinder, if x or y is periodic or the tube leaves the box.
Region make_region(const Box& box, const PackingBounds& packing, double radius, const RegionSpec& spec);

// Fixed-bin histogram on [lo, hi) with under/overflow counts, and the sum of the values that fell
// in each bin (for the value-weighted density).
class Histogram {
 public:
  Histogram() = default;
  Histogram(double lo, double hi, std::size_t bins);
  void add(double value);
  void merge(const Histogram& other);
  std::size_t bins() const { return counts_.size(); }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  double width() const { return (hi_ - lo_) / static_cast<double>(counts_.size()); }
  double bin_lo(std::size_t i) const { return lo_ + width() * static_cast<double>(i); }
  double bin_centre(std::size_t i) const { return lo_ + width() * (static_cast<double>(i) + 0.5); }
  std::uint64_t count(std::size_t i) const { return counts_[i]; }
  std::uint64_t underflow() const { return underflow_; }
  std::uint64_t overflow() const { return overflow_; }
  std::uint64_t total() const { return total_; }
  double sum(std::size_t i) const { return sums_[i]; }
  // Probability density n(x) in bin i, normalised by every value added (in range or not): its
  // integral over the bins is the fraction of values in range.
  double density(std::size_t i) const;
  // The value-weighted density x n(x) averaged over bin i: the sum of the values in the bin over
  // (every value added x width). Exact bin by bin (no bin-centre approximation), so its integral
  // over the bins is the sum of the in-range values over their total count: the mean <x> when
  // none is out of range.
  double weighted_density(std::size_t i) const;

 private:
  double lo_ = 0.0, hi_ = 1.0;
  std::vector<std::uint64_t> counts_;
  std::vector<double> sums_;
  std::uint64_t underflow_ = 0, overflow_ = 0, total_ = 0;
};

struct HistogramSpec {
  double xi_max = config::kDefaultXiMax;
  std::size_t bins = config::kDefaultBins;
};

// Statistics of the selected pores of one frame or of many frames pooled (section IV.B):
//  * P(xi) = xi.density(); the paper's rho_v(xi) = xi^3 P(xi);
//  * n_v(v) = v.density(): the number density of v = xi^3, P(xi) / (3 xi^2); integral 1;
//  * rho_v(v) = v.weighted_density() = v n_v(v) = (xi/3) P(xi): the paper's volume distribution
//    in v, rho_v(v) dv = xi^3 P(xi) dxi, whose integral is nu ("nu = int xi^3 P(xi) dxi =
//    int rho_v(v) dv"), the function of the claim rho_v(v) ~ exp(-v/nu);
//  * nu = <xi^3>, exact from the pores.
struct PoreStatistics {
  explicit PoreStatistics(const HistogramSpec& spec = {});
  void add(const Pore& pore);
  void merge(const PoreStatistics& other);
  double nu() const;       // mean normalised pore volume <xi^3> (NaN without pores)
  double mean_xi() const;  // NaN without pores
  std::size_t pores = 0;
  std::size_t degenerate = 0;  // pores merged from several tetrahedra
  double sum_xi = 0.0, sum_xi3 = 0.0;
  Histogram xi, v;
};

// Gotoh's P0(sigma) in the Percus-Yevick approximation (paper, section IV.B): eq. 8 for
// sigma <= 1 and, for sigma >= 1, the scaled-particle/Percus-Yevick form that replaces the
// printed eq. 9 (continuous with two derivatives at sigma = 1; doc/tapmc-pores.rst).
double gotoh_p0(double sigma, double phi);

// Measured P0(sigma): the fraction of random points farther than sigma R from every centre.
struct P0Statistics {
  P0Statistics(double sigma_max = config::kDefaultSigmaMax, std::size_t steps = config::kDefaultSigmaBins);
  void add_distance(double distance_over_radius);
  void merge(const P0Statistics& other);
  std::size_t steps() const { return farther.size(); }
  double sigma(std::size_t k) const { return sigma_max * static_cast<double>(k) / static_cast<double>(steps() - 1); }
  double p0(std::size_t k) const;
  // Volume fraction seen by the samples: the fraction of points inside a sphere (1 - P0(1)).
  double phi() const;
  double sigma_max;
  std::vector<std::uint64_t> farther;  // samples with distance > sigma_k R
  std::uint64_t samples = 0, inside = 0;
};

// Uniform random points in the region (3 count coordinates; in its disk with a cylinder),
// reproducible from (seed, stream).
std::vector<double> random_points(const Region& region, std::size_t count, std::uint64_t seed, std::uint64_t stream);

// Radius of a monodisperse frame: the radius column's common value, or `fallback` (> 0) when the
// dump has none. Throws RadiusError with the two extreme atoms when polydisperse, or
// when the column disagrees with a given fallback.
struct RadiusCheck {
  double radius = 0.0;
  std::size_t index_min = 0, index_max = 0;  // extreme atoms (for messages)
};
class RadiusError : public std::invalid_argument {
 public:
  RadiusError(const std::string& what, std::size_t index) : std::invalid_argument(what), index(index) {}
  std::size_t index;  // the atom (input position) the message is about
};
RadiusCheck common_radius(const Frame& frame, double fallback, double tolerance = config::kPolydisperseTolerance);

}  // namespace pores
}  // namespace tapmc

#endif
