// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Cell list of the hard-sphere Monte Carlo kernel: cells at least one contact distance wide,
// a fixed number of padded slots per cell in structure-of-arrays layout, and a ring of empty
// cells around the grid, so a 27-cell overlap test has no branches and no bounds checks.
#ifndef TAPMC_CELL_GRID_H
#define TAPMC_CELL_GRID_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tapmc {

// One axis of the grid. Real cells are 0..cells-1; stored ("padded") cell p = real cell + 1,
// with empty cells at p = 0 and p = cells + 1. For cell c and offset o in {-1, 0, +1}
// (k = o + 1), neighbour[3c + k] is the padded index of the neighbour and shift[3c + k] the
// image shift added to separations (nonzero only across a periodic boundary).
struct GridAxis {
  double lo = 0.0, width = 1.0, inv_width = 1.0, length = 0.0;
  int cells = 1;
  bool periodic = false;
  std::vector<int> neighbour;
  std::vector<double> shift;

  // Cells of width >= min_width covering [lo, lo + extent); periodic: extent is the period.
  // At most max_cells cells (wider cells if needed).
  void setup(double lo, double extent, double min_width, bool periodic, int max_cells);

  // Real cell of coordinate x, clamped to [0, cells): points outside the covered range land
  // in the edge cell, which keeps every pair closer than one width within one cell step.
  int cell_of(double x) const
  {
    double t = (x - lo) * inv_width;
    if (!(t > 0.0)) return 0;
    if (t >= static_cast<double>(cells)) return cells - 1;
    return static_cast<int>(t);
  }
};

class CellGrid {
 public:
  // Coordinate of empty slots and of a sphere hidden during its own trial: its squared
  // distance to any real point (1e60) dwarfs every contact threshold, with no overflow.
  static constexpr double kFar = 1e30;

  // Sets up empty storage for spheres 0..n_spheres-1; slots per cell is rounded up to a
  // multiple of 4; with_radius adds a radius row per cell (polydisperse).
  void reset(const std::array<GridAxis, 3> &axes, int slots, bool with_radius, int n_spheres);

  const GridAxis &axis(int d) const { return axes_[d]; }
  int slots() const { return slots_; }
  int rows() const { return rows_; }      // 3 (x, y, z) or 4 (+ radius)
  int stride() const { return stride_; }  // doubles per cell block = rows * slots
  int padded(int d) const { return axes_[d].cells + 2; }

  int cell_index(int px, int py, int pz) const { return (pz * padded(1) + py) * padded(0) + px; }
  int locate(double x, double y, double z) const
  {
    return cell_index(axes_[0].cell_of(x) + 1, axes_[1].cell_of(y) + 1, axes_[2].cell_of(z) + 1);
  }
  // Real (unpadded) cell coordinates of a padded cell index.
  void real_coords(int cell, int &ix, int &iy, int &iz) const
  {
    const int px = padded(0), py = padded(1);
    ix = cell % px - 1;
    iy = (cell / px) % py - 1;
    iz = cell / (px * py) - 1;
  }

  double *block(int cell) { return data_.get() + static_cast<std::size_t>(cell) * stride_; }
  const double *block(int cell) const
  {
    return data_.get() + static_cast<std::size_t>(cell) * stride_;
  }
  const double *data() const { return data_.get(); }
  int count(int cell) const { return count_[cell]; }
  int owner(int cell, int slot) const { return owner_[static_cast<std::size_t>(cell) * slots_ + slot]; }
  int home_cell(int id) const { return home_cell_[id]; }
  int home_slot(int id) const { return home_slot_[id]; }

  double x(int id) const { return block(home_cell_[id])[home_slot_[id]]; }
  double y(int id) const { return block(home_cell_[id])[slots_ + home_slot_[id]]; }
  double z(int id) const { return block(home_cell_[id])[2 * slots_ + home_slot_[id]]; }

  // Puts sphere id into cell `cell`. Returns true if the cell was full and the storage had to
  // grow (slots doubled): callers specialised on slots() must then re-dispatch.
  bool insert(int id, int cell, double x, double y, double z, double r);
  // Takes sphere id out of its cell (the cell's last sphere fills the hole).
  void remove(int id);
  // New position inside the same cell.
  void set_position(int id, double x, double y, double z)
  {
    double *b = block(home_cell_[id]);
    const int s = home_slot_[id];
    b[s] = x;
    b[slots_ + s] = y;
    b[2 * slots_ + s] = z;
  }
  // Moves sphere id to a position in another cell. Returns true if the storage grew.
  bool relocate(int id, int new_cell, double x, double y, double z, double r)
  {
    remove(id);
    return insert(id, new_cell, x, y, z, r);
  }

  // Largest number of spheres in one cell.
  int max_count() const;

 private:
  struct FreeAligned {
    void operator()(double *p) const;
  };
  void allocate(std::size_t n_cells);
  void grow();

  std::array<GridAxis, 3> axes_;
  int slots_ = 4, rows_ = 3, stride_ = 12;
  std::size_t n_cells_ = 0;
  std::unique_ptr<double[], FreeAligned> data_;
  std::vector<int> count_, owner_, home_cell_, home_slot_;
};

}  // namespace tapmc

#endif
