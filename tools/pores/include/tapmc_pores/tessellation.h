// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Pores of a frame of equal spheres: Voronoi vertices of the centres from CGAL's exact-predicate
// 3-D Delaunay triangulation, with exact periodic images and merged degenerate vertices.
#ifndef TAPMC_PORES_TESSELLATION_H
#define TAPMC_PORES_TESSELLATION_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

#include "tapmc_pores/dump_reader.h"
#include "tapmc_pores/pores_config.h"

namespace tapmc {
namespace pores {

// One pore: a Voronoi vertex of the centres (paper, section IV.B; doc/tapmc-pores.rst).
struct Pore {
  std::array<double, 3> centre{};        // wrapped into [lo, hi) along periodic directions
  double xi = 0.0;                       // (circumradius - R) / R: the tangent empty sphere
  std::array<std::int64_t, 4> ids{};     // atom ids of the four centres of one of its tetrahedra
  int tetrahedra = 1;                    // Delaunay tetrahedra merged into it (> 1: degenerate)
  double volume = 0.0;                   // volume of its Delaunay cell (sum of those tetrahedra)
};

struct PoreOptions {
  double radius = 0.0;  // R, the common radius of the spheres (required, > 0)
  double merge_tolerance = config::kMergeTolerance;
  double overlap_tolerance = config::kOverlapTolerance;
  double padding_over_radius = config::kPaddingOverRadius;
  int max_padding_retries = config::kMaxPaddingRetries;
  // Region of interest (box coordinates): only cells whose pore centre lies in it may ask for a
  // wider padding. Wider cells outside it (free-surface hull cells, typically) are counted as
  // unresolved instead of growing the padding for everybody. Default: everywhere.
  std::array<double, 3> focus_lo{{-1e300, -1e300, -1e300}};
  std::array<double, 3> focus_hi{{1e300, 1e300, 1e300}};
};

struct PoreResult {
  std::size_t pore_count = 0;        // Voronoi vertices of the (periodic) centres, each once
  std::size_t tetrahedra = 0;        // Delaunay tetrahedra behind those pores
  double tetrahedra_volume = 0.0;    // their total volume (= box volume when triply periodic)
  std::size_t unresolved = 0;        // Delaunay cells whose empty sphere exceeds the padding
  std::size_t unresolved_in_focus = 0;  // ... of which centred in the region of interest (focus)
  double retry_padding = 0.0;        // padding that would resolve the resolvable ones (0: none)
  double padding = 0.0;              // padding finally used (length units)
  int attempts = 1;                  // triangulations built (> 1: padding was grown)
  double triangulation_seconds = 0;  // time in CGAL's Delaunay construction (all attempts)
  double pore_seconds = 0;           // time in circumspheres, merging, canonical selection
};

// Spheres closer than the threshold 2R (1 - overlap tolerance): the deepest overlapping pair
// (the closest pair, always a Delaunay edge). `index_*` are positions in the input.
class OverlapError : public std::runtime_error {
 public:
  OverlapError(const std::string& what, std::size_t index_a, std::size_t index_b, double distance, double threshold,
               double depth, std::size_t pairs)
      : std::runtime_error(what), index_a(index_a), index_b(index_b), distance(distance), threshold(threshold),
        depth(depth), pairs(pairs) {}
  std::size_t index_a, index_b;
  double distance;   // centre distance of the pair
  double threshold;  // 2R (1 - overlap tolerance): pairs closer than this are refused
  double depth;      // overlap relative to a diameter: 1 - distance / 2R
  std::size_t pairs; // overlapping pairs among Delaunay neighbours (at least this many overlap)
};

class Tessellation {
 public:
  // xyz: 3 n centres inside the box along periodic directions ([lo, hi)); ids: n atom ids.
  // Throws std::invalid_argument on bad arguments, OverlapError on overlapping spheres,
  // std::runtime_error when a periodic box is too small for its pores.
  Tessellation(const Box& box, const std::vector<double>& xyz, const std::vector<std::int64_t>& ids,
               const PoreOptions& options);
  ~Tessellation();
  Tessellation(const Tessellation&) = delete;
  Tessellation& operator=(const Tessellation&) = delete;

  const PoreResult& result() const;

  // Every pore once (in no particular order), built on the fly: a 10^6-sphere frame has
  // 6.5 10^6 pores, which the streaming form never holds in memory at once.
  void for_each_pore(const std::function<void(const Pore&)>& visit) const;
  std::vector<Pore> pores() const;  // the same, collected

  // Distance from each point (3 count coordinates, inside the box along periodic directions) to
  // the nearest sphere centre, periodic images included (Gotoh's P0 sampling).
  std::vector<double> nearest_centre_distances(const std::vector<double>& points) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pores
}  // namespace tapmc

#endif
