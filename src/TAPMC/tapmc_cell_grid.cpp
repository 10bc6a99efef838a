// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Neighbour search grid of the redeposition kernel: axis set-up and binning.
#include "tapmc_cell_grid.h"

#include <algorithm>
#include <cmath>

namespace tapmc {

void GridAxis::setup(double lo_in, double extent, double min_width, bool periodic_in,
                     int max_cells)
{
  lo = lo_in;
  periodic = periodic_in;
  length = periodic ? extent : 0.0;
  const double fit = std::floor(extent / min_width);
  cells = static_cast<int>(std::clamp(fit, 1.0, static_cast<double>(std::max(1, max_cells))));
  // Rounding of extent / cells must not leave a cell narrower than min_width.
  while (cells > 1 && extent / cells < min_width) --cells;
  width = periodic ? extent / cells : std::max(extent / cells, min_width);
  inv_width = 1.0 / width;

  neighbour.assign(3 * static_cast<std::size_t>(cells), 0);
  shift.assign(3 * static_cast<std::size_t>(cells), 0.0);
  for (int c = 0; c < cells; ++c) {
    for (int k = 0; k < 3; ++k) {
      int n = c + k - 1;  // real neighbour, may be -1 or cells
      double s = 0.0;
      if (periodic) {
        // Wrapped neighbour: its spheres seen at x - L (left of cell 0) or x + L (right of
        // the last cell).
        if (n < 0) {
          n += cells;
          s = -length;
        } else if (n >= cells) {
          n -= cells;
          s = length;
        }
      }
      neighbour[3 * c + k] = n + 1;  // padded index; -1 and cells map to the empty ring
      shift[3 * c + k] = s;
    }
  }
}

void CellGrid::build(const std::array<GridAxis, 3> &axes, const double *xyz,
                     const double *radius, int n)
{
  axes_ = axes;
  const GridAxis &ax = axes_[0], &ay = axes_[1], &az = axes_[2];
  const int px = ax.cells + 2, py = ay.cells + 2, pz = az.cells + 2;
  cell_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(px) * py * pz + 1, 0);
  for (int i = 0; i < n; ++i) {
    const double *p = xyz + 3 * i;
    cell_[i] = ((az.cell_of(p[2]) + 1) * py + ay.cell_of(p[1]) + 1) * px + ax.cell_of(p[0]) + 1;
    ++cell_start_[cell_[i] + 1];
  }
  max_count_ = 0;
  for (std::size_t c = 1; c < cell_start_.size(); ++c) {
    max_count_ = std::max(max_count_, cell_start_[c]);
    cell_start_[c] += cell_start_[c - 1];
  }
  // Counting sort, stable: within a cell, spheres in index order.
  binned_.resize(n);
  for (int i = 0; i < n; ++i) binned_[cell_start_[cell_[i]]++] = i;
  for (std::size_t c = cell_start_.size() - 1; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
  cell_start_[0] = 0;
  // Coordinates in cell order: the candidates of one cell are contiguous.
  binned_xyzr_.resize(4 * static_cast<std::size_t>(n));
  double *b = binned_xyzr_.data();
  for (int q = 0; q < n; ++q) {
    const int j = binned_[q];
    for (int d = 0; d < 3; ++d) b[4 * q + d] = xyz[3 * j + d];
    b[4 * q + 3] = radius[j];
  }
}

}  // namespace tapmc
