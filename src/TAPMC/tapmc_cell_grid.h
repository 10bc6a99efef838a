// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The neighbour search of the redeposition kernel: spheres binned into cells at least one search
// radius wide, and one visitor over the 27 cells around a point that hands every binned sphere
// to a per-pair action (a lambda, inlined). The violation check (tapmc_settle.cpp) searches
// through it; the trial-move engine (tapmc_sphere_mover.cpp) bins on its axes (GridAxis).
#ifndef TAPMC_CELL_GRID_H
#define TAPMC_CELL_GRID_H

#include <array>
#include <cstddef>
#include <type_traits>
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
  // Bins the n spheres xyz (interleaved x, y, z; periodic axes already wrapped into the box)
  // of radius radius[i]. Within a cell the spheres keep their index order. Storage is reused
  // between builds.
  void build(const std::array<GridAxis, 3> &axes, const double *xyz, const double *radius, int n);

  const GridAxis &axis(int d) const { return axes_[d]; }
  // A periodic axis with fewer than 3 cells makes the stencil visit a sphere more than once
  // (through several images).
  bool visits_repeat() const
  {
    return (axes_[0].periodic && axes_[0].cells < 3) || (axes_[1].periodic && axes_[1].cells < 3);
  }
  // Upper bound on the spheres one visit hands to its action (27 cells of the fullest size).
  std::size_t max_visited() const { return 27 * static_cast<std::size_t>(max_count_); }

  // Calls visit(j, pj, shift_x, shift_y) for every sphere j binned in the 27 cells around
  // (x, y, z), cell by cell (z, then y, then x offset from -1 to +1), where pj points to x, y, z,
  // R of j and shift_x / shift_y is the image shift of j's cell (0 or +-L). The action returns
  // true to stop the search; visit_neighbours then returns true. An action taking a fifth
  // argument also gets shift_z, the image shift along a periodic z (the contact counter's fully
  // periodic boxes, tapmc_contacts.h); the packing kernels never make z periodic.
  template <class Visit>
  bool visit_neighbours(double x, double y, double z, Visit &&visit) const
  {
    constexpr bool with_z = std::is_invocable_v<Visit &, int, const double *, double, double,
                                                 double>;
    const GridAxis &ax = axes_[0], &ay = axes_[1], &az = axes_[2];
    const int px = ax.cells + 2, py = ay.cells + 2;
    const int ix = 3 * ax.cell_of(x), iy = 3 * ay.cell_of(y), iz = 3 * az.cell_of(z);
    const int *binned = binned_.data();
    const double *xyzr = binned_xyzr_.data();
    for (int kz = 0; kz < 3; ++kz)
      for (int ky = 0; ky < 3; ++ky)
        for (int kx = 0; kx < 3; ++kx) {
          const int c = (az.neighbour[iz + kz] * py + ay.neighbour[iy + ky]) * px +
                        ax.neighbour[ix + kx];
          const double shift_x = ax.shift[ix + kx], shift_y = ay.shift[iy + ky];
          const int q1 = cell_start_[c + 1];
          for (int q = cell_start_[c]; q < q1; ++q) {
            if constexpr (with_z) {
              if (visit(binned[q], xyzr + 4 * q, shift_x, shift_y, az.shift[iz + kz])) return true;
            } else {
              if (visit(binned[q], xyzr + 4 * q, shift_x, shift_y)) return true;
            }
          }
        }
    return false;
  }

 private:
  std::array<GridAxis, 3> axes_;
  int max_count_ = 0;
  std::vector<int> cell_, cell_start_, binned_;  // CSR: spheres of padded cell c at
                                                 // binned_[cell_start_[c] .. cell_start_[c + 1])
  std::vector<double> binned_xyzr_;              // x, y, z, R of binned_[q] at 4q
};

}  // namespace tapmc

#endif
