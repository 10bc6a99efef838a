// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Cell list of the hard-sphere Monte Carlo kernel: axis set-up, storage, insert/remove/grow.
#include "tapmc_cell_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <new>
#include <stdexcept>

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

void CellGrid::FreeAligned::operator()(double *p) const { std::free(p); }

void CellGrid::allocate(std::size_t n_cells)
{
  const std::size_t bytes = n_cells * static_cast<std::size_t>(stride_) * sizeof(double);
  const std::size_t rounded = (bytes + 63) / 64 * 64;
  void *p = std::aligned_alloc(64, rounded > 0 ? rounded : 64);
  if (!p) throw std::bad_alloc();
  data_.reset(static_cast<double *>(p));
  std::fill(data_.get(), data_.get() + n_cells * stride_, kFar);
}

void CellGrid::reset(const std::array<GridAxis, 3> &axes, int slots, bool with_radius,
                     int n_spheres)
{
  axes_ = axes;
  slots_ = std::max(4, (slots + 3) / 4 * 4);
  rows_ = with_radius ? 4 : 3;
  stride_ = rows_ * slots_;
  n_cells_ = static_cast<std::size_t>(padded(0)) * padded(1) * padded(2);
  allocate(n_cells_);
  if (with_radius)  // empty slots: radius 0 (their distance already rules them out)
    for (std::size_t c = 0; c < n_cells_; ++c)
      std::fill_n(data_.get() + c * stride_ + 3 * slots_, slots_, 0.0);
  count_.assign(n_cells_, 0);
  owner_.assign(n_cells_ * slots_, -1);
  home_cell_.assign(n_spheres, -1);
  home_slot_.assign(n_spheres, -1);
}

void CellGrid::grow()
{
  const int old_slots = slots_;
  std::unique_ptr<double[], FreeAligned> old_data = std::move(data_);
  const std::vector<int> old_owner = owner_;
  const int old_stride = stride_;
  slots_ = 2 * old_slots;
  stride_ = rows_ * slots_;
  allocate(n_cells_);
  owner_.assign(n_cells_ * slots_, -1);
  for (std::size_t c = 0; c < n_cells_; ++c) {
    double *dst = data_.get() + c * stride_;
    const double *src = old_data.get() + c * old_stride;
    for (int row = 0; row < rows_; ++row)
      std::copy_n(src + row * old_slots, old_slots, dst + row * slots_);
    if (rows_ == 4) std::fill_n(dst + 3 * slots_ + old_slots, slots_ - old_slots, 0.0);
    std::copy_n(old_owner.begin() + c * old_slots, old_slots, owner_.begin() + c * slots_);
  }
}

bool CellGrid::insert(int id, int cell, double x, double y, double z, double r)
{
  bool grew = false;
  if (count_[cell] == slots_) {
    grow();
    grew = true;
  }
  const int s = count_[cell]++;
  double *b = block(cell);
  b[s] = x;
  b[slots_ + s] = y;
  b[2 * slots_ + s] = z;
  if (rows_ == 4) b[3 * slots_ + s] = r;
  owner_[static_cast<std::size_t>(cell) * slots_ + s] = id;
  home_cell_[id] = cell;
  home_slot_[id] = s;
  return grew;
}

void CellGrid::remove(int id)
{
  const int cell = home_cell_[id];
  const int s = home_slot_[id];
  const int last = --count_[cell];
  double *b = block(cell);
  int *own = owner_.data() + static_cast<std::size_t>(cell) * slots_;
  if (s != last) {
    for (int row = 0; row < rows_; ++row) b[row * slots_ + s] = b[row * slots_ + last];
    own[s] = own[last];
    home_slot_[own[s]] = s;
  }
  for (int row = 0; row < 3; ++row) b[row * slots_ + last] = kFar;
  if (rows_ == 4) b[3 * slots_ + last] = 0.0;
  own[last] = -1;
  home_cell_[id] = -1;
  home_slot_[id] = -1;
}

int CellGrid::max_count() const
{
  int m = 0;
  for (int c : count_) m = std::max(m, c);
  return m;
}

}  // namespace tapmc
