// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Exact stereology of sphere packings (paper, sections III and IV.A): horizontal and vertical cuts.
//
// Every packing fraction here is an exact volume integral of sphere material (closed forms, no
// sampling): the mean of the cut fraction Phi over a set of parallel planes is the volume
// fraction of the region they sweep. Functions come in two layers:
//  - one-sphere geometry (a sphere centred at the origin), and
//  - accumulations over a set of spheres that ADD un-normalised sums (areas, volumes, counts)
//    into caller buffers, so that a parallel caller sums over its own spheres, reduces the
//    buffer once, then normalises with the finish_* functions. The serial convenience
//    functions (summarize, profile) chain the same pieces.
#ifndef TAPMC_STEREOLOGY_H
#define TAPMC_STEREOLOGY_H

#include "tapmc_cylinder.h"
#include "tapmc_defaults.h"

#include <optional>
#include <vector>

namespace tapmc {
namespace stereo {

// ---- one sphere, centre at the origin -------------------------------------------------------
// Volume of {lo <= z <= hi} inside a sphere of the given radius (a slab of a sphere).
double sphere_slab_volume(double radius, double lo, double hi);
// Area of {lo <= t <= hi} inside a disk of radius rho (t: a coordinate through the centre).
double disk_band_area(double rho, double lo, double hi);
// Volume of {x >= p, z >= q} inside the unit sphere (two perpendicular cutting planes).
double unit_sphere_quadrant_volume(double p, double q);
// Volume of {xlo <= x <= xhi, zlo <= z <= zhi} inside a sphere of the given radius (y free).
double sphere_box_band_volume(double radius, double xlo, double xhi, double zlo, double zhi);

// ---- inputs ---------------------------------------------------------------------------------
// A set of spheres, read in place: sphere k is xyz[3 m], xyz[3 m + 1], xyz[3 m + 2] with
// m = index ? index[k] : k, for k < count; radius[m] or, when radius == nullptr, uniform_radius.
struct Spheres {
  const double *xyz = nullptr;
  const double *radius = nullptr;
  double uniform_radius = 0.0;
  const int *index = nullptr;
  int count = 0;
};

// Orthogonal box. Horizontal cuts have area (hi[0]-lo[0]) (hi[1]-lo[1]); a periodic x or y
// makes vertical cuts see images of the spheres. z is never periodic (the floor is at the bottom).
struct Box {
  double lo[3] = {0.0, 0.0, 0.0};
  double hi[3] = {1.0, 1.0, 1.0};
  bool periodic[2] = {true, true};
  double length(int dim) const { return hi[dim] - lo[dim]; }
  double horizontal_area() const { return length(0) * length(1); }
};

// n planes at the centres of n equal bins tiling [lo, hi]: plane k sits at lo + (k + 1/2) w,
// bin k is [lo + k w, lo + (k + 1) w], w = (hi - lo) / n.
struct PlaneGrid {
  double lo = 0.0;
  double hi = 1.0;
  int n = 1;
  double bin_width() const { return (hi - lo) / n; }
  double position(int k) const { return lo + (k + 0.5) * bin_width(); }
};
// Throws std::invalid_argument unless n >= 1 and lo < hi (naming the setting and its value).
void validate(const PlaneGrid &grid);

// ---- sums over spheres (add into the caller's accumulators) --------------------------------
// Sum of the disk areas cut by the plane z (a disk crossing a periodic side counts whole).
double horizontal_cut_area(const Spheres &spheres, double z);
// Volume of sphere material in the slab z0 <= z <= z1 (= integral of the cut area over z).
double horizontal_slab_volume(const Spheres &spheres, double z0, double z1);
// Vertical cut perpendicular to axis (0: x, 1: y) at coordinate c, restricted to za <= z <= zb:
// the sum of the chord-disk areas of all spheres (and their periodic images along axis).
double vertical_cut_area(const Spheres &spheres, const Box &box, int axis, double c, double za,
                         double zb);
// Volume of sphere material in c0 <= (coordinate along axis) <= c1, za <= z <= zb, with periodic
// images along axis when the box is periodic there.
double vertical_slab_volume(const Spheres &spheres, const Box &box, int axis, double c0,
                            double c1, double za, double zb);

// Adds, for every plane k of the grid, the cut area at the plane to cut_area[k] and the volume
// of its bin to bin_volume[k]. axis 2: horizontal planes; axis 0 / 1: vertical planes restricted
// to za <= z <= zb (za, zb ignored for axis 2).
void accumulate_profile(const Spheres &spheres, const Box &box, int axis, const PlaneGrid &grid,
                        double za, double zb, double *cut_area, double *bin_volume);

// ---- surface height (defines the top of the <Phi^c> window) -------------------------------
// The horizontal box is split into nx * ny columns, each about `width` wide (n = max(1,
// floor(L / width)) per direction, exactly tiling the box). A sphere belongs to the column of
// its centre (wrapped when periodic, clamped otherwise).
struct ColumnGrid {
  double lo[2] = {0.0, 0.0};
  double width[2] = {1.0, 1.0};
  int n[2] = {1, 1};
  bool periodic[2] = {true, true};
  int size() const { return n[0] * n[1]; }
  int column_of(double x, double y) const;
};
// Columns `width` wide (the last digits of L / width forgiven, kColumnCountRounding), at most
// kMaxColumnsPerAxis a direction: a narrower width throws, unless `widen` (the default width,
// not the user's), which then widens the columns of that direction to L / kMaxColumnsPerAxis.
ColumnGrid make_column_grid(const Box &box, double width, bool widen = false);
// tops[c] = max(tops[c], z_i + R_i) over the spheres of column c (initialise with -infinity;
// combine ranks with a MAX reduction).
void accumulate_column_tops(const Spheres &spheres, const ColumnGrid &grid, double *tops);
// Mean of the finite column tops (empty columns are skipped); `fallback` when all are empty.
double surface_height(const double *tops, int ncolumns, double fallback);

// ---- the global measures (Phi_b, <Phi^c>, <Z>, lateral and central means) ------------------
// User choices; unset optionals take their defaults from the mean radius (tapmc_defaults.h).
struct SummarySettings {
  double floor = 0.0;                   // z_floor
  double top_fraction = defaults::kTopFraction;    // z_top = floor + top_fraction (h_s - floor)
  double wall_factor = defaults::kWallBandFactor;  // perturbed-zone correction of the wall band
  int transverse_axis = 0;              // vertical cuts perpendicular to x (0) or y (1)
  std::optional<double> bulk_height;    // Phi_b slab height (default 4 R)
  std::optional<double> wall_band;      // corrected band height (default R)
  std::optional<double> lateral_width;  // lateral zone width (default 7 R)
  std::optional<double> column_width;   // surface column width (default 2 R)
  std::optional<double> window_lo;      // vertical-cut z-window (default floor + 2 R ..
  std::optional<double> window_hi;      //   z_top), absolute z
};

// Every height and zone, resolved from the settings, the box, the mean radius and h_s.
struct Windows {
  double floor = 0.0;
  double bulk_top = 0.0;        // Phi_b slab: [floor, bulk_top]
  double wall_band_top = 0.0;   // corrected band: [floor, wall_band_top] (<= top)
  double surface = 0.0;         // h_s
  double top = 0.0;             // z_top (>= floor)
  double wall_factor = 1.0;
  int transverse_axis = 0;
  double window_lo = 0.0;       // vertical cuts: [window_lo, window_hi]
  double window_hi = 0.0;
  double lateral_lo_end = 0.0;  // lateral zones [box lo, lateral_lo_end], [lateral_hi_start,
  double lateral_hi_start = 0.0;//   box hi] along transverse_axis, central zone in between
  double lateral_width = 0.0;   // the lateral setting resolved (before clipping at the middle)
  // Width of the central zone along transverse_axis: 0 when the lateral zones meet at the
  // middle of the box (lateral_width >= half the box length).
  double central_width() const { return lateral_hi_start - lateral_lo_end; }
};

// Throws std::invalid_argument if a setting is outside its range (naming it).
void validate(const SummarySettings &settings);
// The grid of h_s for `settings`: its column width, else the default 2R widened where the box
// is more than kMaxColumnsPerAxis of them wide.
ColumnGrid surface_column_grid(const Box &box, const SummarySettings &settings,
                               double mean_radius);
double resolved_column_width(const SummarySettings &settings, double mean_radius);
double resolved_lateral_width(const SummarySettings &settings, double mean_radius);
Windows resolve_windows(const SummarySettings &settings, const Box &box, double mean_radius,
                        double surface);
// The default z-window of the vertical cuts (also used by the profile along x or y).
void default_vertical_window(const SummarySettings &settings, const Windows &w,
                             double mean_radius, double &za, double &zb);

// Layout of the summary accumulator (sum these over ranks).
enum SummarySum {
  kSphereCount,
  kHeightSum,       // sum of (z_i - floor)
  kBulkVolume,      // [floor, bulk_top]
  kWallBandVolume,  // [floor, wall_band_top]
  kUpperVolume,     // [wall_band_top, top]
  kLateralVolume,   // lateral zones x window
  kCentralVolume,   // central zone x window
  kNumSummarySums
};
void accumulate_summary(const Spheres &spheres, const Box &box, const Windows &w, double *sums);

struct Summary {
  double phi_bulk = 0.0;         // Phi_b
  double phi_corrected = 0.0;    // <Phi^c>
  double mean_height = 0.0;      // <Z>
  double top = 0.0;              // z_top
  double phi_lateral = 0.0;      // lateral zone volume fraction
  double phi_central = 0.0;      // central zone volume fraction; NaN when the zone is empty
                                 // (Windows::central_width() == 0: no measurement)
  double surface = 0.0;          // h_s
  double sphere_count = 0.0;
};
Summary finish_summary(const double *sums, const Box &box, const Windows &w);

// Serial convenience: the whole chain for spheres held by one process.
double mean_radius(const Spheres &spheres);
Summary summarize(const Spheres &spheres, const Box &box, const SummarySettings &settings);

// ---- profiles ---------------------------------------------------------------------------------
// rows[3 k + 0] plane position, rows[3 k + 1] Phi at the plane, rows[3 k + 2] exact mean of Phi
// over bin k, from the reduced cut_area / bin_volume sums. Phi of a vertical cut is normalised
// by (length of the box along the other horizontal axis) * (zb - za): NaN if zb <= za (an empty
// window measures nothing; a 0 would read as an empty layer).
void finish_profile(const double *cut_area, const double *bin_volume, const Box &box, int axis,
                    const PlaneGrid &grid, double za, double zb, double *rows);
std::vector<double> profile(const Spheres &spheres, const Box &box, int axis,
                            const PlaneGrid &grid, double za, double zb);

// ---- a cylindrical container (tapmc_cylinder.h) ---------------------------------------------
// Every measure counts only the sphere material inside the container's disk (or inside the
// coaxial cylinder of a radial bin): exact for any input, also for a sphere poking through the
// wall of an invalid packing. A sphere wholly inside takes the closed forms above; one cut by a
// cylinder takes sphere_cylinder_slab_volume (tapmc_cylinder.h, quadrature to ~1e-15 R^3).

// Phi(z) over the disk (the horizontal cuts of the tube, paper section III): sum of the areas of
// the cut disks inside the container's disk at height z, and the sphere volume inside the
// container in z0 <= z <= z1. Divide by pi radius^2 (and z1 - z0).
double cylinder_cut_area(const Spheres &spheres, const Cylinder &cylinder, double z);
double cylinder_slab_volume(const Spheres &spheres, const Cylinder &cylinder, double z0,
                            double z1);
// Adds, for every horizontal plane k of the grid (along z), the cut area inside the disk at the
// plane to cut_area[k] and the volume inside the container in its bin to bin_volume[k].
void accumulate_cylinder_profile(const Spheres &spheres, const Cylinder &cylinder,
                                 const PlaneGrid &grid, double *cut_area, double *bin_volume);
// rows[3 k + 0] plane height, rows[3 k + 1] Phi at the plane, rows[3 k + 2] exact mean of Phi
// over bin k (the layout of finish_profile), over the disk's area pi radius^2.
void finish_cylinder_profile(const double *cut_area, const double *bin_volume,
                             const Cylinder &cylinder, const PlaneGrid &grid, double *rows);
std::vector<double> cylinder_profile(const Spheres &spheres, const Cylinder &cylinder,
                                     const PlaneGrid &grid);

// The radial profile, the tube's transversal profile: the grid's bins are coaxial annuli
// [r_k, r_k+1] (radii from the container's axis, grid.lo >= 0) restricted to za <= z <= zb, its
// planes the coaxial cylindrical surfaces at the bin centres. Adds the sphere area on surface k
// (within the z-window) to cut_area[k] and the sphere volume in annulus k to bin_volume[k].
// Throws std::invalid_argument for a grid with lo < 0 (as validate(PlaneGrid)).
void accumulate_radial_profile(const Spheres &spheres, const Cylinder &cylinder,
                               const PlaneGrid &radii, double za, double zb, double *cut_area,
                               double *bin_volume);
// rows[3 k + 0] radius of surface k, rows[3 k + 1] Phi on it (area / (2 pi r (zb - za))),
// rows[3 k + 2] the volume fraction of annulus k (volume / (pi (r_k+1^2 - r_k^2) (zb - za)));
// NaN if zb <= za (an empty window).
void finish_radial_profile(const double *cut_area, const double *bin_volume,
                           const PlaneGrid &radii, double za, double zb, double *rows);
std::vector<double> radial_profile(const Spheres &spheres, const Cylinder &cylinder,
                                   const PlaneGrid &radii, double za, double zb);

// The wall zone of the tube (FIG. 8's zone within 7R of the side walls, here the annulus within
// wall_width of the wall: radius - wall_width <= r <= radius) and the core inside it, over the
// z-window [za, zb]. Sums to add up over ranks:
enum CylinderZoneSum { kCylinderWallVolume, kCylinderCoreVolume, kNumCylinderZoneSums };
// Throws std::invalid_argument unless wall_width > 0 (naming it).
void accumulate_cylinder_zones(const Spheres &spheres, const Cylinder &cylinder,
                               double wall_width, double za, double zb, double *sums);
struct CylinderZones {
  double phi_wall = 0.0;     // volume fraction of the wall annulus
  double phi_core = 0.0;     // of the core; NaN when the wall zone covers the disk (no core)
  double core_radius = 0.0;  // max(0, radius - wall_width)
};
CylinderZones finish_cylinder_zones(const double *sums, const Cylinder &cylinder,
                                    double wall_width, double za, double zb);
CylinderZones cylinder_zones(const Spheres &spheres, const Cylinder &cylinder,
                             double wall_width, double za, double zb);

// The global measures in the tube (compute stereo/profile with a container): the Summary of the
// box with the container's disk, pi radius^2, in place of the box's cross-section, and FIG. 8's
// wall zone and core in place of the lateral and central zones. The windows come from
// resolve_windows over the container's bounding box (column grid of h_s, heights); the wall
// zone is the annulus within w.lateral_width of the wall. The sums keep the SummarySum layout:
// kBulkVolume, kWallBandVolume and kUpperVolume count only material inside the container,
// kLateralVolume is the wall zone's and kCentralVolume the core's, over [window_lo, window_hi].
// Throws std::invalid_argument unless w.lateral_width > 0.
void accumulate_cylinder_summary(const Spheres &spheres, const Cylinder &cylinder,
                                 const Windows &w, double *sums);
// phi_lateral is the wall zone's volume fraction, phi_central the core's (NaN without a core:
// lateral_width >= radius).
Summary finish_cylinder_summary(const double *sums, const Cylinder &cylinder, const Windows &w);
// The container's horizontal bounding square (non-periodic): the column grid of h_s in the tube.
Box bounding_box(const Cylinder &cylinder, double zlo, double zhi);
// Serial convenience: the whole chain in the tube (summarize's steps with the container).
Summary summarize_cylinder(const Spheres &spheres, const Cylinder &cylinder,
                           const SummarySettings &settings);

}  // namespace stereo
}  // namespace tapmc

#endif
