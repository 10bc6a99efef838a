// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The sequential deposition's storage: the layered grid (columns in x and y, layers in z added as
// the packing grows, linked lists of sphere indices per cell, a height map of column tops) and the
// deposited spheres with the planes of the domain, which every contact and event search reads.
// Inline: their methods run in the hot loops of the searches (tapmc_deposition_paths.cpp,
// tapmc_deposition_cylinder.cpp).
#ifndef TAPMC_DEPOSITION_GRID_H
#define TAPMC_DEPOSITION_GRID_H

#include "tapmc_contact.h"
#include "tapmc_deposition.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition_detail.h"
#include "tapmc_math.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tapmc {
namespace deposition_detail {

// ---------------------------------------------------------------------------------------------
// 3-D grid: columns in x and y (periodic wrap or clamped at walls), layers in z from the floor,
// added as the packing grows; linked lists of sphere indices per cell; height map of column tops.
class LayeredGrid {
 public:
  // Columns at least min_width wide, at most max_columns in all and
  // defaults::kGridMaxCellsPerSideAxis along an axis (wider columns beyond): a wide box of few
  // spheres would otherwise allocate a grid of its area (10 spheres in a box 20000 diameters
  // wide: 4.8 GB).
  void setup(const DepositionDomain &d, double min_width, long max_columns)
  {
    lx_ = d.xhi - d.xlo;
    ly_ = d.yhi - d.ylo;
    xlo_ = d.xlo;
    ylo_ = d.ylo;
    zf_ = d.z_floor;
    px_ = d.periodic_x;
    py_ = d.periodic_y;
    const double side_cap = defaults::kGridMaxCellsPerSideAxis;
    double nx = std::clamp(std::floor(lx_ / min_width), 1.0, side_cap);
    double ny = std::clamp(std::floor(ly_ / min_width), 1.0, side_cap);
    const double cap = static_cast<double>(std::max(1L, max_columns));
    if (nx * ny > cap) {
      const double widen = std::sqrt(nx * ny / cap);
      nx = std::clamp(std::floor(nx / widen), 1.0, cap);
      ny = std::clamp(std::floor(ny / widen), 1.0, std::floor(cap / nx));
    }
    nx_ = static_cast<int>(nx);
    ny_ = static_cast<int>(ny);
    hx_ = lx_ / nx_;
    hy_ = ly_ / ny_;
    hz_ = min_width;
    layers_ = 0;
    head_.clear();
    next_.clear();
    top_.assign(static_cast<std::size_t>(nx_) * ny_, -kInf);
  }

  int column_x(double x) const { return std::clamp(static_cast<int>(std::floor((x - xlo_) / hx_)), 0, nx_ - 1); }
  int column_y(double y) const { return std::clamp(static_cast<int>(std::floor((y - ylo_) / hy_)), 0, ny_ - 1); }
  int layer_of(double z) const { return std::max(0, static_cast<int>(std::floor((z - zf_) / hz_))); }
  int layers() const { return layers_; }
  int columns_x() const { return nx_; }
  int columns_y() const { return ny_; }
  double layer_width() const { return hz_; }
  double floor_z() const { return zf_; }

  void insert(std::int32_t index, double x, double y, double z, double r)
  {
    const int iz = layer_of(z);
    while (layers_ <= iz) {
      head_.resize(head_.size() + static_cast<std::size_t>(nx_) * ny_, -1);
      ++layers_;
    }
    if (next_.size() <= static_cast<std::size_t>(index)) next_.resize(index + 1, -1);
    const std::size_t column = static_cast<std::size_t>(column_y(y)) * nx_ + column_x(x);
    const std::size_t cell = static_cast<std::size_t>(iz) * nx_ * ny_ + column;
    next_[index] = head_[cell];
    head_[cell] = index;
    top_[column] = std::max(top_[column], z + r);
  }

  // Calls f(index, shift_x, shift_y, image_x, image_y) for every sphere whose cell meets the
  // box [x0, x1] x [y0, y1] (unwrapped coordinates) in layers iz0..iz1; periodic images come
  // with the shift to add to the stored centre.
  template <class F>
  void visit(double x0, double x1, double y0, double y1, int iz0, int iz1, F &&f) const
  {
    iz0 = std::max(iz0, 0);
    iz1 = std::min(iz1, layers_ - 1);
    if (iz0 > iz1) return;
    int ix0, ix1, iy0, iy1;
    column_range(x0, x1, hx_, xlo_, nx_, px_, ix0, ix1);
    column_range(y0, y1, hy_, ylo_, ny_, py_, iy0, iy1);
    for (int iz = iz0; iz <= iz1; ++iz) {
      const std::size_t layer = static_cast<std::size_t>(iz) * nx_ * ny_;
      for (int iy = iy0; iy <= iy1; ++iy) {
        const int image_y = py_ ? static_cast<int>(floor_div(iy, ny_)) : 0;
        const int cy = iy - image_y * ny_;
        const double sy = image_y * ly_;
        for (int ix = ix0; ix <= ix1; ++ix) {
          const int image_x = px_ ? static_cast<int>(floor_div(ix, nx_)) : 0;
          const int cx = ix - image_x * nx_;
          const double sx = image_x * lx_;
          for (std::int32_t i = head_[layer + static_cast<std::size_t>(cy) * nx_ + cx]; i >= 0;
               i = next_[i])
            f(i, sx, sy, image_x, image_y);
        }
      }
    }
  }

  // Highest sphere top among the columns meeting [x0, x1] x [y0, y1] (-inf if none).
  double highest_top(double x0, double x1, double y0, double y1) const
  {
    int ix0, ix1, iy0, iy1;
    column_range(x0, x1, hx_, xlo_, nx_, px_, ix0, ix1);
    column_range(y0, y1, hy_, ylo_, ny_, py_, iy0, iy1);
    double best = -kInf;
    for (int iy = iy0; iy <= iy1; ++iy) {
      const int cy = static_cast<int>(iy - floor_div(iy, ny_) * ny_);
      for (int ix = ix0; ix <= ix1; ++ix) {
        const int cx = static_cast<int>(ix - floor_div(ix, nx_) * nx_);
        best = std::max(best, top_[static_cast<std::size_t>(cy) * nx_ + cx]);
      }
    }
    return best;
  }

 private:
  static void column_range(double a0, double a1, double h, double lo, int n, bool periodic,
                           int &i0, int &i1)
  {
    i0 = static_cast<int>(std::floor((a0 - lo) / h));
    i1 = static_cast<int>(std::floor((a1 - lo) / h));
    if (!periodic) {
      i0 = std::clamp(i0, 0, n - 1);
      i1 = std::clamp(i1, 0, n - 1);
    }
  }

  int nx_ = 1, ny_ = 1, layers_ = 0;
  double hx_ = 1, hy_ = 1, hz_ = 1, lx_ = 1, ly_ = 1, xlo_ = 0, ylo_ = 0, zf_ = 0;
  bool px_ = true, py_ = true;
  std::vector<std::int32_t> head_, next_;
  std::vector<double> top_;
};

// ---------------------------------------------------------------------------------------------
// The spheres deposited so far (centres and radii in insertion order, binned in the layered
// grid) and the planes of the domain: what every contact and event search reads.
struct DepositedSpheres {
  DepositionDomain domain;
  double r_max = 0.0;
  LayeredGrid grid;
  std::vector<double> centres;  // 3 per sphere
  std::vector<double> radii;

  std::size_t size() const { return radii.size(); }

  Vec3 centre_of(std::int32_t i) const
  {
    return {centres[3 * static_cast<std::size_t>(i)], centres[3 * static_cast<std::size_t>(i) + 1],
            centres[3 * static_cast<std::size_t>(i) + 2]};
  }

  void wrap(Vec3 &p) const
  {
    if (domain.periodic_x) p.x = wrap_periodic(p.x, domain.xlo, domain.xhi);
    if (domain.periodic_y) p.y = wrap_periodic(p.y, domain.ylo, domain.yhi);
  }

  void insert(Vec3 p, double r)
  {
    const auto index = static_cast<std::int32_t>(radii.size());
    centres.push_back(p.x);
    centres.push_back(p.y);
    centres.push_back(p.z);
    radii.push_back(r);
    grid.insert(index, p.x, p.y, p.z, r);
  }

  // The planes a sphere of radius r must respect: the floor, and the walls of non-periodic sides
  // (none in a cylinder: its disk lies inside the box, so they are never reached).
  template <class F> void for_each_plane(double r, F &&f) const
  {
    f(Constraint{false, kFloorPlane, 0, 0, {0, 0, 1}, domain.z_floor + r});
    if (domain.has_cylinder) return;
    if (!domain.periodic_x) {
      f(Constraint{false, kWallXlo, 0, 0, {1, 0, 0}, domain.xlo + r});
      f(Constraint{false, kWallXhi, 0, 0, {-1, 0, 0}, -(domain.xhi - r)});
    }
    if (!domain.periodic_y) {
      f(Constraint{false, kWallYlo, 0, 0, {0, 1, 0}, domain.ylo + r});
      f(Constraint{false, kWallYhi, 0, 0, {0, -1, 0}, -(domain.yhi - r)});
    }
  }

  // The cylinder wall for a sphere of radius r (domain.has_cylinder).
  Constraint cylinder_wall(double r) const
  {
    Constraint k{false, kCylinderWall, 0, 0, {domain.cylinder.cx, domain.cylinder.cy, 0.0},
                 domain.cylinder.radius - r};
    k.is_cylinder = true;
    return k;
  }
};

}  // namespace deposition_detail
}  // namespace tapmc

#endif
