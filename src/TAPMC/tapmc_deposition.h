// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Initial packings by sequential gravitational deposition with steepest descent (Jullien & Meakin,
// Europhys. Lett. 4, 1385 (1987)): the loose starting state of the paper (phi = 58.4 % in PBC).
#ifndef TAPMC_DEPOSITION_H
#define TAPMC_DEPOSITION_H

#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace tapmc {

// Where spheres are deposited. Sphere centres stay in z >= z_floor + r (impassable floor); in a
// direction with walls the centres stay in [lo + r, hi - r] (impassable vertical planes, FBC);
// a periodic direction wraps centres into [lo, hi).
// With has_cylinder, the container is the vertical tube `cylinder` instead: centres stay within
// cylinder.radius - r of its axis (its wall is one more support). The tube needs walls in x and y
// (periodic_x = periodic_y = false) and its disk inside [xlo, xhi] x [ylo, yhi], which then only
// bounds the search grid: the flat walls lie outside the tube and are never touched.
struct DepositionDomain {
  double xlo = 0.0, xhi = 1.0;
  double ylo = 0.0, yhi = 1.0;
  bool periodic_x = true;
  bool periodic_y = true;
  double z_floor = 0.0;
  bool has_cylinder = false;
  Cylinder cylinder;
  // deposit_packing() throws std::runtime_error when a sphere comes to rest with its top
  // above z_top (the region or box cannot hold the spheres).
  double z_top = std::numeric_limits<double>::infinity();
};

// Radii uniform in [r_min, r_max]; r_min == r_max is the monodisperse case of the paper.
struct RadiusDistribution {
  double r_min = 1.0;
  double r_max = 1.0;
  static RadiusDistribution monodisperse(double r) { return {r, r}; }
  static RadiusDistribution uniform(double r_min, double r_max) { return {r_min, r_max}; }
  bool is_monodisperse() const { return r_min == r_max; }
};

// Counters of the geometric events, for reports and tests.
struct DepositionStats {
  std::int64_t segments = 0;       // path pieces (fall, roll on one, roll on two) over all drops
  std::int64_t perturbations = 0;  // unstable equilibria (exactly on top of a sphere or a ridge)
                                   // left in a random direction
  std::int64_t wedged = 0;         // unstable equilibria where every way off was blocked by a
                                   // touching wall or sphere: the sphere rests there
  std::int64_t redrops = 0;        // drops abandoned after kDepositionMaxSegments segments and
                                   // restarted from a fresh random (x, y)
  std::int64_t unresolved = 0;     // spheres left, non-overlapping but not proven stable, where
                                   // the last of kDepositionMaxAttempts drops stopped
  std::int64_t wall_rolls = 0;     // of the segments, rolls on one sphere along a cylinder wall
};

enum class RestingOn { Floor, Supports, Unresolved };

struct DropOutcome {
  double x, y, z;   // final centre (x, y wrapped into the box in periodic directions)
  RestingOn rest;   // Floor or Supports: stable; Unresolved: the segment cap was reached
  int segments;     // path pieces of this drop
};

// The deposition engine: a packing that grows one sphere at a time. A 3-D grid of cells of at
// least one maximal diameter (columns in x, y; layers in z added as the packing grows) and a
// height map of column tops make every drop cost O(1) neighbour visits.
// This grid is not the redeposition's CellGrid (tapmc_cell_grid.h), which bins a fixed set of
// spheres once and searches the 27 cells around a point: a deposition adds one sphere per drop,
// in layers that grow with the packing, searches boxes as wide as a roll (up to 2 (r + r_max)
// from the circle centre) and reads column tops. Measured, rebuilding a CellGrid per drop would
// cost up to 0.1 ms a drop at N = 4096 and 4-10 ms at N = 1e5 (N^2 in all), against 35-70 us
// for a whole drop today, and its cells made wide enough for a roll hold 8 times the spheres per
// search (229 instead of 29). The kernels have no shared 3-vector type (they read interleaved
// x, y, z arrays), so the Vec3 of tapmc_deposition_detail.h stays private to the deposition.
class SequentialDeposition {
 public:
  // max_radius bounds every radius ever added (sets the grid spacing). Throws
  // std::invalid_argument naming the offending value (extent below one diameter, radius <= 0; a
  // cylinder with a periodic side, not wider than max_radius, or not inside the box).
  // expected_spheres, when known (> 0), bounds the grid's columns by the packing's size
  // (defaults::kGridCellsPerSphere per sphere) rather than by the box's area alone.
  SequentialDeposition(const DepositionDomain &domain, double max_radius, std::uint64_t seed,
                       std::int64_t expected_spheres = 0);
  ~SequentialDeposition();
  SequentialDeposition(SequentialDeposition &&) noexcept;
  SequentialDeposition &operator=(SequentialDeposition &&) noexcept;

  // Put a sphere in place without any descent (an obstacle or support of later drops).
  void add_fixed_sphere(double x, double y, double z, double radius);

  // Drop a sphere of the given radius vertically at (x, y) from above everything it could touch,
  // then follow steepest descent: vertical fall, rolling on one support, rolling on two, until it
  // rests on the floor or on three supports (spheres or walls) that balance gravity, i.e. its
  // centre's vertical projection lies inside the triangle of its supports. In a cylinder, the
  // curved wall also holds a sphere with one sphere alone at the lowest point of their common
  // path (the sphere, the wall's normal and the vertical in one plane, the sphere on the far
  // side of the axis from the supporting sphere's centre). The sphere joins the
  // packing when the outcome is stable (rest != Unresolved). The random directions used to leave
  // an unstable equilibrium are the stream size() of purpose kDepositionEquilibria under the
  // seed (tapmc_random.h), so a drop is reproducible.
  DropOutcome drop(double x, double y, double radius);

  std::size_t size() const;
  // Centre i (3 doubles) and radius i, in insertion order.
  const double *centre(std::size_t i) const;
  double radius(std::size_t i) const;
  const DepositionStats &stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What create_packing asks for, in the kernel's terms: n spheres of radii uniform in
// [R (1 - W), R (1 + W)] with mass density rho.
struct PackingParams {
  std::int64_t n = 0;        // number of spheres, in [1, 2^31 - 2]
  double radius = 1.0;       // R, the mean radius: > 0 and finite
  double dispersity = 0.0;   // W, in [0, 1)
  double density = defaults::kDepositionDensity;  // rho > 0: each sphere weighs rho 4/3 pi r^3
  RadiusDistribution radii() const
  {
    return RadiusDistribution::uniform(radius * (1.0 - dispersity), radius * (1.0 + dispersity));
  }
};
// Throws std::invalid_argument naming the first bad parameter (N, R, dispersity, density), its
// value and its allowed range.
void validate(const PackingParams &params);

struct Packing {
  std::vector<double> xyz;     // 3 per sphere, deposition order
  std::vector<double> radius;  // 1 per sphere
  DepositionStats stats;
};

// The Jullien-Meakin packing: n spheres with radii drawn from `radii`, each dropped at a uniform
// random (x, y) (in [lo + r, hi - r] along wall directions; in a cylinder, uniform on the disk of
// radius cylinder.radius - r about its axis). Deterministic in (n, radii, domain,
// seed): sphere i draws its radius and drop points from the counter-based stream i of purpose
// kDepositionDrops under the seed (tapmc_random.h), so the result does not depend on how many
// processes compute it.
// Throws std::invalid_argument for bad input (n < 0, r_min <= 0, r_max < r_min, an extent below
// one diameter) and std::runtime_error when a sphere's top ends above domain.z_top.
Packing deposit_packing(std::int64_t n, const RadiusDistribution &radii,
                        const DepositionDomain &domain, std::uint64_t seed);

// Which spheres touch the domain's cylinder wall (1) or not (0), with the deposition's support
// tolerance (gap below kDepositionSupportTolerance of the diameter): the spheres the wall holds.
// All 0 without a cylinder.
std::vector<std::uint8_t> cylinder_wall_contacts(const Packing &packing,
                                                 const DepositionDomain &domain);

// The bulk window of a deposit, away from the floor and from the rough top:
// [z_floor + margin, z_floor + 2 <z - z_floor> - margin], where 2 <z - z_floor> (twice the
// mean centre height) is the height of a uniform slab with the same centre mean height.
// create_packing uses margin = kDepositionBulkMarginOverRadius mean radii.
void bulk_window(const Packing &packing, const DepositionDomain &domain, double margin,
                 double &z0, double &z1);

// Volume fraction of the packing's spheres in the slab z0 <= z <= z1 over the domain's x-y
// extent: the stereology kernel's exact slab integral (tapmc_stereology.h; whole spheres count
// across periodic sides).
double slab_volume_fraction(const Packing &packing, const DepositionDomain &domain, double z0,
                            double z1);

}  // namespace tapmc

#endif
