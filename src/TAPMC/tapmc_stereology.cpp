// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Exact stereology kernels: closed-form sphere volumes and their sums in a box or a cylinder.
#include "tapmc_stereology.h"

#include "tapmc_checks.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tapmc {
namespace stereo {

namespace {

// floor(u) as a bin index, clamped to [-1, n] before the cast: a sphere millions of bins wide
// (bins of 1e-13 diameter) reached beyond int, and the cast gave INT_MIN on x86: the sphere
// was skipped and its bins read 0.
int bin_floor(double u, int n)
{
  return static_cast<int>(std::clamp(std::floor(u), -1.0, static_cast<double>(n)));
}

// Visits every sphere as visit(x, y, z, radius); the two layout choices (per-sphere radius or
// not, index list or not) are taken once, outside the loops.
template <class Visit> void for_each_sphere(const Spheres &s, Visit &&visit)
{
  const double *xyz = s.xyz;
  if (s.radius) {
    const double *r = s.radius;
    if (s.index) {
      for (int k = 0; k < s.count; ++k) {
        const int m = s.index[k];
        visit(xyz[3 * m], xyz[3 * m + 1], xyz[3 * m + 2], r[m]);
      }
    } else {
      for (int m = 0; m < s.count; ++m) visit(xyz[3 * m], xyz[3 * m + 1], xyz[3 * m + 2], r[m]);
    }
  } else {
    const double r = s.uniform_radius;
    if (s.index) {
      for (int k = 0; k < s.count; ++k) {
        const int m = s.index[k];
        visit(xyz[3 * m], xyz[3 * m + 1], xyz[3 * m + 2], r);
      }
    } else {
      for (int m = 0; m < s.count; ++m) visit(xyz[3 * m], xyz[3 * m + 1], xyz[3 * m + 2], r);
    }
  }
}

// Volume of {z >= t} inside the unit sphere (a cap of height 1 - t).
double unit_cap_volume(double t)
{
  if (t >= 1.0) return 0.0;
  if (t <= -1.0) return 4.0 * kPi / 3.0;
  return kPi * (1.0 - t) * (1.0 - t) * (2.0 + t) / 3.0;
}

// Area of {u <= t} inside a disk of radius rho, |t| <= rho.
double disk_area_below(double rho, double t)
{
  // (rho - t)(rho + t), not rho^2 - t^2: exact zero at t = +-rho even with fused multiply-add
  const double h = std::sqrt(std::max(0.0, (rho - t) * (rho + t)));
  const double s = std::clamp(t / rho, -1.0, 1.0);
  return t * h + rho * rho * std::asin(s) + 0.5 * kPi * rho * rho;
}

// Range of periodic image shifts k (centre + k L) that can reach [lo, hi] with reach `radius`.
// A non-periodic direction has the single image k = 0.
struct ImageRange {
  int first = 0;
  int last = 0;
};
ImageRange image_range(bool periodic, double centre, double radius, double lo, double hi,
                       double period)
{
  if (!periodic) return {0, 0};
  return {static_cast<int>(std::ceil((lo - centre - radius) / period)),
          static_cast<int>(std::floor((hi - centre + radius) / period))};
}


}  // namespace

// ---- one sphere -------------------------------------------------------------------------------

double sphere_slab_volume(double radius, double lo, double hi)
{
  const double a = std::max(lo, -radius);
  const double b = std::min(hi, radius);
  if (!(a < b)) return 0.0;
  // integral of pi (R^2 - u^2) du over [a, b], written without cancellation of R^2 b - R^2 a
  return kPi * (b - a) * (radius * radius - (a * a + a * b + b * b) / 3.0);
}

double disk_band_area(double rho, double lo, double hi)
{
  if (!(rho > 0.0)) return 0.0;
  const double a = std::max(lo, -rho);
  const double b = std::min(hi, rho);
  if (!(a < b)) return 0.0;
  return disk_area_below(rho, b) - disk_area_below(rho, a);
}

// For p, q >= 0 and p^2 + q^2 < 1 (derivation: integrate the chord-disk area
// s^2 acos(q / s) - q sqrt(s^2 - q^2), s^2 = 1 - x^2, over x from p by parts):
//   V = 2/3 atan2(D, p q) + 2/3 p q D - p (1 - p^2/3) acos(q / sqrt(1 - p^2))
//       - q (1 - q^2/3) acos(p / sqrt(1 - q^2)),   D = sqrt(1 - p^2 - q^2).
// The acos terms are written atan2(D, q) and atan2(D, p): every term then uses the same D, and
// dV/dD = 0 at D = 0, so rounding in D costs only O(dD^2) where the sphere is barely cut.
// Negative p or q follow by reflection: {x >= p} = everything minus the mirror of {x >= -p}.
double unit_sphere_quadrant_volume(double p, double q)
{
  if (p >= 1.0 || q >= 1.0) return 0.0;
  if (p < 0.0) return unit_cap_volume(q) - unit_sphere_quadrant_volume(-p, q);
  if (q < 0.0) return unit_cap_volume(p) - unit_sphere_quadrant_volume(p, -q);
  const double d2 = (1.0 - p) * (1.0 + p) - q * q;
  if (d2 <= 0.0) return 0.0;
  const double d = std::sqrt(d2);
  const double v = (2.0 / 3.0) * (std::atan2(d, p * q) + p * q * d) -
                   p * (1.0 - p * p / 3.0) * std::atan2(d, q) -
                   q * (1.0 - q * q / 3.0) * std::atan2(d, p);
  return std::max(0.0, v);
}

double sphere_box_band_volume(double radius, double xlo, double xhi, double zlo, double zhi)
{
  if (!(xlo < xhi) || !(zlo < zhi)) return 0.0;
  if (xlo >= radius || xhi <= -radius || zlo >= radius || zhi <= -radius) return 0.0;
  const double inv = 1.0 / radius;
  const double pa = std::max(-1.0, xlo * inv), pb = std::min(1.0, xhi * inv);
  const double qa = std::max(-1.0, zlo * inv), qb = std::min(1.0, zhi * inv);
  // inclusion-exclusion: [pa, pb) x [qa, qb) = Q(pa,qa) - Q(pb,qa) - Q(pa,qb) + Q(pb,qb)
  const double v = unit_sphere_quadrant_volume(pa, qa) - unit_sphere_quadrant_volume(pb, qa) -
                   unit_sphere_quadrant_volume(pa, qb) + unit_sphere_quadrant_volume(pb, qb);
  return std::max(0.0, v) * radius * radius * radius;
}

// ---- sums over spheres -----------------------------------------------------------------------

double horizontal_cut_area(const Spheres &spheres, double z)
{
  double area = 0.0;
  for_each_sphere(spheres, [&](double, double, double zc, double r) {
    const double u = z - zc;
    if (std::fabs(u) < r) area += kPi * (r - u) * (r + u);
  });
  return area;
}

double horizontal_slab_volume(const Spheres &spheres, double z0, double z1)
{
  double volume = 0.0;
  for_each_sphere(spheres, [&](double, double, double zc, double r) {
    volume += sphere_slab_volume(r, z0 - zc, z1 - zc);
  });
  return volume;
}

namespace {
// Visits every image of every sphere that can reach [lo, hi] along axis (0: x, 1: y) as
// visit(centre, zc, r), centre = the image's coordinate along axis (the sphere itself when the
// axis is not periodic).
template <class Visit>
void for_each_image(const Spheres &spheres, const Box &box, int axis, double lo, double hi,
                    Visit &&visit)
{
  const bool periodic = box.periodic[axis];
  const double period = box.length(axis);
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    const double centre = axis == 0 ? x : y;
    const ImageRange images = image_range(periodic, centre, r, lo, hi, period);
    for (int k = images.first; k <= images.last; ++k) visit(centre + k * period, zc, r);
  });
}
}  // namespace

double vertical_cut_area(const Spheres &spheres, const Box &box, int axis, double c, double za,
                         double zb)
{
  double area = 0.0;
  for_each_image(spheres, box, axis, c, c, [&](double centre, double zc, double r) {
    const double dx = c - centre;
    const double rho2 = (r - dx) * (r + dx);
    if (rho2 > 0.0) area += disk_band_area(std::sqrt(rho2), za - zc, zb - zc);
  });
  return area;
}

double vertical_slab_volume(const Spheres &spheres, const Box &box, int axis, double c0,
                            double c1, double za, double zb)
{
  if (!(c0 < c1) || !(za < zb)) return 0.0;
  double volume = 0.0;
  for_each_image(spheres, box, axis, c0, c1, [&](double centre, double zc, double r) {
    volume += sphere_box_band_volume(r, c0 - centre, c1 - centre, za - zc, zb - zc);
  });
  return volume;
}

void validate(const PlaneGrid &grid)
{
  if (!(grid.n >= 1)) throw_outside_range("planes n", grid.n, "[1, +inf)");
  if (!(grid.lo < grid.hi))
    throw_outside_range("planes lo", grid.lo, "(-inf, hi) = (-inf, " + number(grid.hi) + ")");
}

void accumulate_profile(const Spheres &spheres, const Box &box, int axis, const PlaneGrid &grid,
                        double za, double zb, double *cut_area, double *bin_volume)
{
  if (!(axis >= 0 && axis <= 2)) throw_outside_range("axis", axis, "{0, 1, 2}");
  validate(grid);
  const int n = grid.n;
  const double w = grid.bin_width();
  const double inv_w = 1.0 / w;
  // Bins [first, last] that [lo, hi] reaches (clamped to the grid).
  auto bin_range = [&](double lo, double hi, int &first, int &last) {
    first = std::max(0, bin_floor((lo - grid.lo) * inv_w, n));
    last = std::min(n - 1, bin_floor((hi - grid.lo) * inv_w, n));
  };

  if (axis == 2) {
    for_each_sphere(spheres, [&](double, double, double zc, double r) {
      int first, last;
      bin_range(zc - r, zc + r, first, last);
      for (int k = first; k <= last; ++k) {
        const double u = grid.position(k) - zc;
        if (std::fabs(u) < r) cut_area[k] += kPi * (r - u) * (r + u);
        const double edge = grid.lo + k * w;
        bin_volume[k] += sphere_slab_volume(r, edge - zc, edge + w - zc);
      }
    });
    return;
  }
  if (!(za < zb)) return;
  const bool periodic = box.periodic[axis];
  const double period = box.length(axis);
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    const double centre = axis == 0 ? x : y;
    if (za - zc >= r || zb - zc <= -r) return;  // the sphere misses the z-window
    const ImageRange images = image_range(periodic, centre, r, grid.lo, grid.hi, period);
    for (int img = images.first; img <= images.last; ++img) {
      const double shifted = centre + img * period;
      int first, last;
      bin_range(shifted - r, shifted + r, first, last);
      for (int k = first; k <= last; ++k) {
        const double dx = grid.position(k) - shifted;
        const double rho2 = (r - dx) * (r + dx);
        if (rho2 > 0.0) cut_area[k] += disk_band_area(std::sqrt(rho2), za - zc, zb - zc);
        const double edge = grid.lo + k * w - shifted;
        bin_volume[k] += sphere_box_band_volume(r, edge, edge + w, za - zc, zb - zc);
      }
    }
  });
}

// ---- surface height --------------------------------------------------------------------------

int ColumnGrid::column_of(double x, double y) const
{
  const double c[2] = {x, y};
  int idx[2];
  for (int d = 0; d < 2; ++d) {
    int i = static_cast<int>(std::floor((c[d] - lo[d]) / width[d]));
    if (periodic[d]) {
      i %= n[d];
      if (i < 0) i += n[d];
    } else {
      i = std::clamp(i, 0, n[d] - 1);
    }
    idx[d] = i;
  }
  return idx[0] + n[0] * idx[1];
}

ColumnGrid make_column_grid(const Box &box, double width, bool widen)
{
  if (!(width > 0.0)) throw_outside_range("column width", width, "(0, +inf)");
  ColumnGrid g;
  for (int d = 0; d < 2; ++d) {
    const double length = box.length(d);
    if (!(length > 0.0))
      throw_outside_range(std::string("box length along ") + "xy"[d], length, "(0, +inf)");
    g.lo[d] = box.lo[d];
    double columns = std::floor(length / width + defaults::kColumnCountRounding);
    if (widen) columns = std::min(columns, static_cast<double>(defaults::kMaxColumnsPerAxis));
    if (!(columns <= defaults::kMaxColumnsPerAxis))
      throw_outside_range("column width", width,
                          "[" + number(length / defaults::kMaxColumnsPerAxis) +
                              ", +inf) (at most " + std::to_string(defaults::kMaxColumnsPerAxis) +
                              " columns along " + "xy"[d] + ")");
    g.n[d] = std::max(1, static_cast<int>(columns));
    g.width[d] = length / g.n[d];
    g.periodic[d] = box.periodic[d];
  }
  return g;
}

void accumulate_column_tops(const Spheres &spheres, const ColumnGrid &grid, double *tops)
{
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    double &top = tops[grid.column_of(x, y)];
    top = std::max(top, zc + r);
  });
}

double surface_height(const double *tops, int ncolumns, double fallback)
{
  double sum = 0.0;
  int filled = 0;
  for (int c = 0; c < ncolumns; ++c) {
    if (!std::isfinite(tops[c])) continue;
    sum += tops[c];
    ++filled;
  }
  return filled ? sum / filled : fallback;
}

// ---- global measures -------------------------------------------------------------------------

void validate(const SummarySettings &s)
{
  if (!(s.top_fraction > 0.0 && s.top_fraction <= 1.0))
    throw_outside_range("top_fraction", s.top_fraction, "(0, 1]");
  if (!(s.wall_factor > 0.0)) throw_outside_range("wall_factor", s.wall_factor, "(0, +inf)");
  if (!(s.transverse_axis == 0 || s.transverse_axis == 1))
    throw_outside_range("transverse axis", s.transverse_axis, "{0 (x), 1 (y)}");
  auto positive = [](const std::optional<double> &v, const char *name) {
    if (v && !(*v > 0.0)) throw_outside_range(name, *v, "(0, +inf)");
  };
  positive(s.bulk_height, "bulk");
  positive(s.wall_band, "wall_band");
  positive(s.lateral_width, "lateral");
  positive(s.column_width, "column");
  if (s.window_lo.has_value() != s.window_hi.has_value())
    throw std::invalid_argument("window needs both za and zb");
  if (s.window_lo && !(*s.window_lo < *s.window_hi))
    throw_outside_range("window za", *s.window_lo,
                        "(-inf, zb) = (-inf, " + number(*s.window_hi) + ")");
}

double resolved_column_width(const SummarySettings &settings, double mean_radius)
{
  return settings.column_width.value_or(defaults::kSurfaceColumnOverRadius * mean_radius);
}

ColumnGrid surface_column_grid(const Box &box, const SummarySettings &settings,
                               double mean_radius)
{
  return make_column_grid(box, resolved_column_width(settings, mean_radius),
                          !settings.column_width.has_value());
}

double resolved_lateral_width(const SummarySettings &settings, double mean_radius)
{
  return settings.lateral_width.value_or(defaults::kLateralWidthOverRadius * mean_radius);
}

Windows resolve_windows(const SummarySettings &s, const Box &box, double mean_radius,
                        double surface)
{
  Windows w;
  w.floor = s.floor;
  w.surface = surface;
  w.top = s.floor + s.top_fraction * std::max(0.0, surface - s.floor);
  w.bulk_top = s.floor + s.bulk_height.value_or(defaults::kBulkHeightOverRadius * mean_radius);
  w.wall_band_top = std::min(
      w.top, s.floor + s.wall_band.value_or(defaults::kWallBandOverRadius * mean_radius));
  w.wall_factor = s.wall_factor;
  w.transverse_axis = s.transverse_axis;
  default_vertical_window(s, w, mean_radius, w.window_lo, w.window_hi);
  // lateral zones of width `lateral` at both faces, never overlapping (clipped at the middle)
  const int a = s.transverse_axis;
  const double lateral = resolved_lateral_width(s, mean_radius);
  w.lateral_width = lateral;
  const double middle = 0.5 * (box.lo[a] + box.hi[a]);
  w.lateral_lo_end = std::min(box.lo[a] + lateral, middle);
  w.lateral_hi_start = std::max(box.hi[a] - lateral, middle);
  return w;
}

void default_vertical_window(const SummarySettings &s, const Windows &w, double mean_radius,
                             double &za, double &zb)
{
  za = s.window_lo.value_or(s.floor + defaults::kVerticalWindowBottomOverRadius * mean_radius);
  zb = s.window_hi.value_or(w.top);
}

void accumulate_summary(const Spheres &spheres, const Box &box, const Windows &w, double *sums)
{
  const int a = w.transverse_axis;
  const bool periodic = box.periodic[a];
  const double period = box.length(a);
  const double za = w.window_lo, zb = w.window_hi;
  const bool window_open = za < zb;
  double count = 0.0, heights = 0.0, bulk = 0.0, band = 0.0, upper = 0.0, lateral = 0.0,
         central = 0.0;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    count += 1.0;
    heights += zc - w.floor;
    bulk += sphere_slab_volume(r, w.floor - zc, w.bulk_top - zc);
    band += sphere_slab_volume(r, w.floor - zc, w.wall_band_top - zc);
    upper += sphere_slab_volume(r, w.wall_band_top - zc, w.top - zc);
    if (!window_open || za - zc >= r || zb - zc <= -r) return;
    const double centre = a == 0 ? x : y;
    const ImageRange images = image_range(periodic, centre, r, box.lo[a], box.hi[a], period);
    for (int k = images.first; k <= images.last; ++k) {
      const double s = centre + k * period;
      lateral += sphere_box_band_volume(r, box.lo[a] - s, w.lateral_lo_end - s, za - zc, zb - zc) +
                 sphere_box_band_volume(r, w.lateral_hi_start - s, box.hi[a] - s, za - zc, zb - zc);
      central +=
          sphere_box_band_volume(r, w.lateral_lo_end - s, w.lateral_hi_start - s, za - zc, zb - zc);
    }
  });
  sums[kSphereCount] += count;
  sums[kHeightSum] += heights;
  sums[kBulkVolume] += bulk;
  sums[kWallBandVolume] += band;
  sums[kUpperVolume] += upper;
  sums[kLateralVolume] += lateral;
  sums[kCentralVolume] += central;
}

namespace {
double ratio(double num, double den) { return den > 0.0 ? num / den : 0.0; }

// The horizontal-cut measures of a Summary (count, <Z>, Phi_b, <Phi^c>, heights) over the
// cross-section `area`: the box's L_x L_y or the tube's disk.
Summary finish_horizontal(const double *sums, double area, const Windows &w)
{
  Summary out;
  out.sphere_count = sums[kSphereCount];
  out.mean_height = ratio(sums[kHeightSum], sums[kSphereCount]);
  out.phi_bulk = ratio(sums[kBulkVolume], area * (w.bulk_top - w.floor));
  out.phi_corrected = ratio(w.wall_factor * sums[kWallBandVolume] + sums[kUpperVolume],
                            area * (w.top - w.floor));
  out.top = w.top;
  out.surface = w.surface;
  return out;
}
}  // namespace

Summary finish_summary(const double *sums, const Box &box, const Windows &w)
{
  const int a = w.transverse_axis;
  const double other = box.length(1 - a);
  const double window = std::max(0.0, w.window_hi - w.window_lo);
  const double lateral_length = (w.lateral_lo_end - box.lo[a]) + (box.hi[a] - w.lateral_hi_start);
  const double central_length = w.central_width();

  Summary out = finish_horizontal(sums, box.horizontal_area(), w);
  // an empty zone or an empty window (a bed of one layer: its top below floor + 2R) has no
  // packing fraction: NaN, not a 0 that reads as a measurement
  const double none = std::numeric_limits<double>::quiet_NaN();
  out.phi_lateral = window > 0.0 ? ratio(sums[kLateralVolume], lateral_length * other * window)
                                 : none;
  out.phi_central = central_length > 0.0 && window > 0.0
                        ? ratio(sums[kCentralVolume], central_length * other * window)
                        : none;
  return out;
}

double mean_radius(const Spheres &spheres)
{
  double sum = 0.0;
  for_each_sphere(spheres, [&](double, double, double, double r) { sum += r; });
  return spheres.count > 0 ? sum / spheres.count : 0.0;
}

namespace {

// The windows of a serial summary: the surface height from the columns tiling `box` (the box, or
// a container's bounding square), then the windows it sets. settings must be valid.
Windows serial_windows(const Spheres &spheres, const Box &box, const SummarySettings &settings)
{
  const double radius = mean_radius(spheres);
  const ColumnGrid grid = surface_column_grid(box, settings, radius);
  std::vector<double> tops(grid.size(), -std::numeric_limits<double>::infinity());
  accumulate_column_tops(spheres, grid, tops.data());
  const double surface = surface_height(tops.data(), grid.size(), settings.floor);
  return resolve_windows(settings, box, radius, surface);
}

}  // namespace

Summary summarize(const Spheres &spheres, const Box &box, const SummarySettings &settings)
{
  validate(settings);
  const Windows w = serial_windows(spheres, box, settings);
  double sums[kNumSummarySums] = {};
  accumulate_summary(spheres, box, w, sums);
  return finish_summary(sums, box, w);
}

// ---- profiles ---------------------------------------------------------------------------------

void finish_profile(const double *cut_area, const double *bin_volume, const Box &box, int axis,
                    const PlaneGrid &grid, double za, double zb, double *rows)
{
  double plane_area;
  if (axis == 2)
    plane_area = box.horizontal_area();
  else
    plane_area = box.length(1 - axis) * std::max(0.0, zb - za);
  // an empty window (zb <= za) cuts no area: NaN, not a 0 that reads as a measurement
  const double inv_area =
      plane_area > 0.0 ? 1.0 / plane_area : std::numeric_limits<double>::quiet_NaN();
  const double inv_bin = inv_area / grid.bin_width();
  for (int k = 0; k < grid.n; ++k) {
    rows[3 * k] = grid.position(k);
    rows[3 * k + 1] = cut_area[k] * inv_area;
    rows[3 * k + 2] = bin_volume[k] * inv_bin;
  }
}

std::vector<double> profile(const Spheres &spheres, const Box &box, int axis,
                            const PlaneGrid &grid, double za, double zb)
{
  std::vector<double> cut(grid.n, 0.0), volume(grid.n, 0.0), rows(3 * grid.n);
  accumulate_profile(spheres, box, axis, grid, za, zb, cut.data(), volume.data());
  finish_profile(cut.data(), volume.data(), box, axis, grid, za, zb, rows.data());
  return rows;
}

// ---- a cylindrical container ----------------------------------------------------------------

namespace {
double axis_distance(const Cylinder &c, double x, double y)
{
  const double dx = x - c.cx, dy = y - c.cy;
  return std::sqrt(dx * dx + dy * dy);
}

// Area of the horizontal cut at height u above the centre of a sphere of radius r whose centre
// is d from the container's axis, inside the container's disk.
double cut_in_disk(double r, double d, double u, double radius)
{
  if (!(std::fabs(u) < r)) return 0.0;
  const double a2 = (r - u) * (r + u);
  if (d + r <= radius) return kPi * a2;  // wholly inside: the closed form, as for the box
  return disk_lens_area(std::sqrt(a2), radius, d);
}
}  // namespace

double cylinder_cut_area(const Spheres &spheres, const Cylinder &cylinder, double z)
{
  double area = 0.0;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    area += cut_in_disk(r, axis_distance(cylinder, x, y), z - zc, cylinder.radius);
  });
  return area;
}

double cylinder_slab_volume(const Spheres &spheres, const Cylinder &cylinder, double z0,
                            double z1)
{
  double volume = 0.0;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    volume += sphere_cylinder_slab_volume(r, axis_distance(cylinder, x, y), cylinder.radius,
                                          z0 - zc, z1 - zc);
  });
  return volume;
}

void accumulate_cylinder_profile(const Spheres &spheres, const Cylinder &cylinder,
                                 const PlaneGrid &grid, double *cut_area, double *bin_volume)
{
  validate(grid);
  const int n = grid.n;
  const double w = grid.bin_width();
  const double inv_w = 1.0 / w;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    const double d = axis_distance(cylinder, x, y);
    if (d >= cylinder.radius + r) return;  // wholly outside the container
    const int first = std::max(0, bin_floor((zc - r - grid.lo) * inv_w, n));
    const int last = std::min(n - 1, bin_floor((zc + r - grid.lo) * inv_w, n));
    for (int k = first; k <= last; ++k) {
      cut_area[k] += cut_in_disk(r, d, grid.position(k) - zc, cylinder.radius);
      const double edge = grid.lo + k * w - zc;
      bin_volume[k] += sphere_cylinder_slab_volume(r, d, cylinder.radius, edge, edge + w);
    }
  });
}

void finish_cylinder_profile(const double *cut_area, const double *bin_volume,
                             const Cylinder &cylinder, const PlaneGrid &grid, double *rows)
{
  const double inv_area = 1.0 / (kPi * cylinder.radius * cylinder.radius);
  const double inv_bin = inv_area / grid.bin_width();
  for (int k = 0; k < grid.n; ++k) {
    rows[3 * k] = grid.position(k);
    rows[3 * k + 1] = cut_area[k] * inv_area;
    rows[3 * k + 2] = bin_volume[k] * inv_bin;
  }
}

std::vector<double> cylinder_profile(const Spheres &spheres, const Cylinder &cylinder,
                                     const PlaneGrid &grid)
{
  validate(cylinder);
  std::vector<double> cut(grid.n, 0.0), volume(grid.n, 0.0), rows(3 * grid.n);
  accumulate_cylinder_profile(spheres, cylinder, grid, cut.data(), volume.data());
  finish_cylinder_profile(cut.data(), volume.data(), cylinder, grid, rows.data());
  return rows;
}

void accumulate_radial_profile(const Spheres &spheres, const Cylinder &cylinder,
                               const PlaneGrid &radii, double za, double zb, double *cut_area,
                               double *bin_volume)
{
  validate(radii);
  if (!(radii.lo >= 0.0)) throw_outside_range("radial bins lo", radii.lo, "[0, hi)");
  if (!(za < zb)) return;
  const int n = radii.n;
  const double w = radii.bin_width();
  const double inv_w = 1.0 / w;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    if (za - zc >= r || zb - zc <= -r) return;  // the sphere misses the z-window
    const double d = axis_distance(cylinder, x, y);
    const double lo = za - zc, hi = zb - zc;
    // annulus k holds V(r_k+1) - V(r_k), V(rho) the volume inside the coaxial cylinder of radius
    // rho; V is 0 below d - r and constant above d + r, so only the bins reaching
    // [d - r, d + r] change, and consecutive bins share their boundary's V
    const int first = std::max(0, bin_floor((d - r - radii.lo) * inv_w, n));
    const int last = std::min(n - 1, bin_floor((d + r - radii.lo) * inv_w, n));
    if (first > last) return;
    double v_below = sphere_cylinder_slab_volume(r, d, radii.lo + first * w, lo, hi);
    for (int k = first; k <= last; ++k) {
      const double v_above = sphere_cylinder_slab_volume(r, d, radii.lo + (k + 1) * w, lo, hi);
      bin_volume[k] += v_above - v_below;
      v_below = v_above;
      cut_area[k] += sphere_cylinder_surface_area(r, d, radii.position(k), lo, hi);
    }
  });
}

void finish_radial_profile(const double *cut_area, const double *bin_volume,
                           const PlaneGrid &radii, double za, double zb, double *rows)
{
  const double height = std::max(0.0, zb - za);
  const double w = radii.bin_width();
  const double nan = std::numeric_limits<double>::quiet_NaN();  // an empty window: no surface
  for (int k = 0; k < radii.n; ++k) {
    const double r_mid = radii.position(k);
    const double r0 = radii.lo + k * w, r1 = r0 + w;
    const double surface = kTwoPi * r_mid * height;
    const double annulus = kPi * (r1 - r0) * (r1 + r0) * height;
    rows[3 * k] = r_mid;
    rows[3 * k + 1] = surface > 0.0 ? cut_area[k] / surface : nan;
    rows[3 * k + 2] = annulus > 0.0 ? bin_volume[k] / annulus : nan;
  }
}

std::vector<double> radial_profile(const Spheres &spheres, const Cylinder &cylinder,
                                   const PlaneGrid &radii, double za, double zb)
{
  validate(cylinder);
  std::vector<double> cut(radii.n, 0.0), volume(radii.n, 0.0), rows(3 * radii.n);
  accumulate_radial_profile(spheres, cylinder, radii, za, zb, cut.data(), volume.data());
  finish_radial_profile(cut.data(), volume.data(), radii, za, zb, rows.data());
  return rows;
}

void accumulate_cylinder_zones(const Spheres &spheres, const Cylinder &cylinder,
                               double wall_width, double za, double zb, double *sums)
{
  if (!(wall_width > 0.0)) throw_outside_range("wall zone width", wall_width, "(0, +inf)");
  if (!(za < zb)) return;
  const double core = std::max(0.0, cylinder.radius - wall_width);
  double wall_volume = 0.0, core_volume = 0.0;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    if (za - zc >= r || zb - zc <= -r) return;
    const double d = axis_distance(cylinder, x, y);
    const double v_core = sphere_cylinder_slab_volume(r, d, core, za - zc, zb - zc);
    const double v_all = sphere_cylinder_slab_volume(r, d, cylinder.radius, za - zc, zb - zc);
    core_volume += v_core;
    wall_volume += v_all - v_core;
  });
  sums[kCylinderWallVolume] += wall_volume;
  sums[kCylinderCoreVolume] += core_volume;
}

CylinderZones finish_cylinder_zones(const double *sums, const Cylinder &cylinder,
                                    double wall_width, double za, double zb)
{
  CylinderZones out;
  const double height = std::max(0.0, zb - za);
  const double radius = cylinder.radius;
  out.core_radius = std::max(0.0, radius - wall_width);
  const double core = out.core_radius;
  const double wall_area = kPi * (radius - core) * (radius + core);
  const double core_area = kPi * core * core;
  // no core or no window height: NaN, not a 0 that reads as a measurement (as Summary's zones)
  const double none = std::numeric_limits<double>::quiet_NaN();
  out.phi_wall = wall_area * height > 0.0 ? sums[kCylinderWallVolume] / (wall_area * height)
                                          : none;
  out.phi_core = core > 0.0 && height > 0.0 ? sums[kCylinderCoreVolume] / (core_area * height)
                                            : none;
  return out;
}

CylinderZones cylinder_zones(const Spheres &spheres, const Cylinder &cylinder,
                             double wall_width, double za, double zb)
{
  validate(cylinder);
  double sums[kNumCylinderZoneSums] = {};
  accumulate_cylinder_zones(spheres, cylinder, wall_width, za, zb, sums);
  return finish_cylinder_zones(sums, cylinder, wall_width, za, zb);
}

void accumulate_cylinder_summary(const Spheres &spheres, const Cylinder &cylinder,
                                 const Windows &w, double *sums)
{
  const double rc = cylinder.radius;
  double count = 0.0, heights = 0.0, bulk = 0.0, band = 0.0, upper = 0.0;
  for_each_sphere(spheres, [&](double x, double y, double zc, double r) {
    count += 1.0;
    heights += zc - w.floor;
    const double d = axis_distance(cylinder, x, y);
    bulk += sphere_cylinder_slab_volume(r, d, rc, w.floor - zc, w.bulk_top - zc);
    band += sphere_cylinder_slab_volume(r, d, rc, w.floor - zc, w.wall_band_top - zc);
    upper += sphere_cylinder_slab_volume(r, d, rc, w.wall_band_top - zc, w.top - zc);
  });
  // the wall zone and the core: the zones' own pass (FIG. 8 in the tube), one traversal each
  double zones[kNumCylinderZoneSums] = {};
  accumulate_cylinder_zones(spheres, cylinder, w.lateral_width, w.window_lo, w.window_hi, zones);
  sums[kSphereCount] += count;
  sums[kHeightSum] += heights;
  sums[kBulkVolume] += bulk;
  sums[kWallBandVolume] += band;
  sums[kUpperVolume] += upper;
  sums[kLateralVolume] += zones[kCylinderWallVolume];
  sums[kCentralVolume] += zones[kCylinderCoreVolume];
}

Summary finish_cylinder_summary(const double *sums, const Cylinder &cylinder, const Windows &w)
{
  Summary out = finish_horizontal(sums, kPi * cylinder.radius * cylinder.radius, w);
  double zones[kNumCylinderZoneSums];
  zones[kCylinderWallVolume] = sums[kLateralVolume];
  zones[kCylinderCoreVolume] = sums[kCentralVolume];
  const CylinderZones z =
      finish_cylinder_zones(zones, cylinder, w.lateral_width, w.window_lo, w.window_hi);
  out.phi_lateral = z.phi_wall;
  out.phi_central = z.phi_core;
  return out;
}

Box bounding_box(const Cylinder &cylinder, double zlo, double zhi)
{
  Box box;
  box.lo[0] = cylinder.cx - cylinder.radius;
  box.hi[0] = cylinder.cx + cylinder.radius;
  box.lo[1] = cylinder.cy - cylinder.radius;
  box.hi[1] = cylinder.cy + cylinder.radius;
  box.lo[2] = zlo;
  box.hi[2] = zhi;
  box.periodic[0] = box.periodic[1] = false;
  return box;
}

Summary summarize_cylinder(const Spheres &spheres, const Cylinder &cylinder,
                           const SummarySettings &settings)
{
  validate(settings);
  validate(cylinder);
  const Box box = bounding_box(cylinder, settings.floor, settings.floor + 1.0);
  const Windows w = serial_windows(spheres, box, settings);
  double sums[kNumSummarySums] = {};
  accumulate_cylinder_summary(spheres, cylinder, w, sums);
  return finish_cylinder_summary(sums, cylinder, w);
}

}  // namespace stereo
}  // namespace tapmc
