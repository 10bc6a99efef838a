// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Contacts within a gap: cell-grid counting of every sphere's contacts and their distribution.
#include "tapmc_contacts.h"

#include "tapmc_checks.h"
#include "tapmc_contact.h"
#include "tapmc_math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tapmc {
namespace contacts {

namespace {
const char kAxisName[3] = {'x', 'y', 'z'};
}  // namespace

void validate(const Settings &s)
{
  if (!(s.gap >= 0.0 && s.gap <= defaults::kContactsMaxGap))
    throw_outside_range("gap", s.gap, "[0, " + number(defaults::kContactsMaxGap) + "]");
  if (s.floor && !std::isfinite(s.floor_z)) throw_outside_range("floor", s.floor_z, "(finite)");
  if (s.wall) tapmc::validate(s.cylinder);
}

double Counter::load(const Spheres &spheres, const Box &box)
{
  const int n = spheres.count;
  if (n > 0 && !spheres.xyz) throw std::invalid_argument("spheres without positions");
  xyz_.resize(3 * static_cast<std::size_t>(n));
  radius_.resize(static_cast<std::size_t>(n));
  double r_max = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = spheres.radius_of(i);
    if (!(r > 0.0 && std::isfinite(r)))
      throw_outside_range("radius of sphere " + std::to_string(i), r, "(0, +inf)");
    radius_[i] = r;
    r_max = std::max(r_max, r);
    for (int d = 0; d < 3; ++d) {
      double x = spheres.xyz[3 * i + d];
      if (!std::isfinite(x))
        throw_outside_range(std::string(1, kAxisName[d]) + " of sphere " + std::to_string(i), x,
                            "(finite)");
      if (box.periodic[d]) x = wrap_periodic(x, box.lo[d], box.hi[d]);
      xyz_[3 * i + d] = x;
    }
  }
  return r_max;
}

// Cells at least `reach` wide (plus a rounding margin) over the period along periodic axes and
// over the spheres along the others; the cell count is capped as in the redeposition kernel.
void Counter::bin(const Box &box, double reach)
{
  const int n = static_cast<int>(radius_.size());
  double mn[3], mx[3], scale = reach;
  for (int d = 0; d < 3; ++d) {
    mn[d] = n > 0 ? xyz_[d] : 0.0;
    mx[d] = mn[d];
  }
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      const double x = xyz_[3 * i + d];
      mn[d] = std::min(mn[d], x);
      mx[d] = std::max(mx[d], x);
      scale = std::max(scale, std::fabs(x));
    }
  const double width = reach + defaults::kGridRoundingMargin * (reach + scale);
  std::array<GridAxis, 3> axes;
  auto set_axis = [&](int d, int max_cells) {
    if (box.periodic[d])
      axes[d].setup(box.lo[d], box.hi[d] - box.lo[d], width, true, max_cells);
    else
      axes[d].setup(mn[d], std::max(mx[d] - mn[d], 0.0), width, false, max_cells);
  };
  set_axis(0, defaults::kGridMaxCellsPerSideAxis);
  set_axis(1, defaults::kGridMaxCellsPerSideAxis);
  const long max_cells =
      defaults::kGridCellsPerSphere * static_cast<long>(n) + defaults::kGridMinCells;
  set_axis(2, static_cast<int>(std::max(
                  1L, max_cells / (static_cast<long>(axes[0].cells) * axes[1].cells))));
  grid_.build(axes, xyz_.data(), radius_.data(), n);
}

void Counter::count(const Spheres &spheres, int centres, const Box &box, const Settings &settings,
                    int *counts, unsigned char *on_floor, unsigned char *on_wall)
{
  validate(settings);
  if (!(centres >= 0 && centres <= spheres.count))
    throw_outside_range("centres", centres, "[0, " + std::to_string(spheres.count) + "]");
  if (settings.floor && box.periodic[2])
    throw std::invalid_argument("a floor needs a non-periodic z (the box is periodic along z)");
  if (settings.wall && (box.periodic[0] || box.periodic[1]))
    throw std::invalid_argument("a container wall needs non-periodic x and y (the box is "
                                "periodic along " +
                                std::string(box.periodic[0] ? "x" : "y") +
                                "): the wall replaces the periodic sides");
  const double r_max = load(spheres, box);
  const double factor = reach_factor(settings.gap);
  const double reach = 2.0 * r_max * factor;  // largest centre distance of a contact
  for (int d = 0; d < 3; ++d) {
    if (!box.periodic[d]) continue;
    const double length = box.hi[d] - box.lo[d];
    // nearest images: no pair may reach two images of one partner
    if (!(length > 2.0 * reach && std::isfinite(length)))
      throw_outside_range(std::string("periodic box length along ") + kAxisName[d], length,
                          "(2 reach, +inf) = (" + number(2.0 * reach) +
                              ", +inf) (reach = 2 R_max (1 + gap))");
  }
  if (centres == 0) return;
  bin(box, reach);

  // Periodicity is in the grid's image shifts (zero along the other axes): one loop for all.
  const double *xyz = xyz_.data();
  const double *radius = radius_.data();
  for (int i = 0; i < centres; ++i) {
    const double xi = xyz[3 * i], yi = xyz[3 * i + 1], zi = xyz[3 * i + 2], ri = radius[i];
    int z = 0;
    grid_.visit_neighbours(xi, yi, zi,
                           [&](int j, const double *pj, double sx, double sy, double sz) {
                             if (j == i) return false;
                             const double reach_ij = (ri + pj[3]) * factor;
                             const double d2 = distance_sq(separation(pj[0], xi, sx),
                                                           separation(pj[1], yi, sy),
                                                           separation(pj[2], zi, sz));
                             z += d2 <= reach_ij * reach_ij ? 1 : 0;
                             return false;
                           });
    const bool floor = settings.floor && touches_floor(zi, ri, settings);
    const bool wall = settings.wall && touches_wall(xi, yi, ri, settings);
    counts[i] = z + (floor ? 1 : 0) + (wall ? 1 : 0);
    if (on_floor) on_floor[i] = floor ? 1 : 0;
    if (on_wall) on_wall[i] = wall ? 1 : 0;
  }
}

std::vector<int> count_contacts(const Spheres &spheres, int centres, const Box &box,
                                const Settings &settings)
{
  std::vector<int> counts(static_cast<std::size_t>(std::max(centres, 0)), 0);
  Counter counter;
  counter.count(spheres, centres, box, settings, counts.data());
  return counts;
}

int accumulate(const int *counts, const unsigned char *on_floor, const unsigned char *on_wall,
               const int *index, int n, double *sums)
{
  int largest = 0;
  for (int k = 0; k < n; ++k) {
    const int m = index ? index[k] : k;
    const int z = counts[m];
    largest = std::max(largest, z);
    sums[kSumSpheres] += 1.0;
    sums[kSumContacts] += z;
    sums[kSumNone] += z == 0 ? 1.0 : 0.0;
    sums[kSumFew] += z < defaults::kContactsFewBelow ? 1.0 : 0.0;
    sums[kSumFloor] += on_floor && on_floor[m] ? 1.0 : 0.0;
    sums[kSumWall] += on_wall && on_wall[m] ? 1.0 : 0.0;
    sums[kSumHistogram + std::min(z, defaults::kContactsMaxZ)] += 1.0;
  }
  return largest;
}

Distribution finish(const double *sums, int max_count)
{
  Distribution d;
  d.fraction.assign(kHistogramRows, 0.0);
  d.spheres = sums[kSumSpheres];
  if (!(d.spheres > 0.0)) return d;
  const double inv = 1.0 / d.spheres;
  d.mean = sums[kSumContacts] * inv;
  d.fraction_none = sums[kSumNone] * inv;
  d.fraction_few = sums[kSumFew] * inv;
  d.fraction_floor = sums[kSumFloor] * inv;
  d.fraction_wall = sums[kSumWall] * inv;
  d.max = max_count;
  for (int z = 0; z < kHistogramRows; ++z) d.fraction[z] = sums[kSumHistogram + z] * inv;
  return d;
}

}  // namespace contacts
}  // namespace tapmc
