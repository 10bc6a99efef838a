// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The plain types of the redeposition (paper, section II) that both of its layers take: the box
// (floor, side walls, periodic axes) and the pick order. The serial kernel (tapmc_settle.h) runs
// on the trial-move engine (tapmc_sphere_mover.h); both include this header, so the engine does
// not depend on the kernel that drives it.
#ifndef TAPMC_SETTLE_TYPES_H
#define TAPMC_SETTLE_TYPES_H

namespace tapmc {

struct SettleBox {
  double lo[3], hi[3];          // box bounds; x, y used for periodic lengths and default walls
  bool periodic[2];             // x, y periodic (z is never periodic: open top)
  bool wall_lo[2], wall_hi[2];  // impassable side planes in non-periodic x / y
  double wall_lo_pos[2], wall_hi_pos[2];  // their positions (sphere needs x - R >= wall_lo_pos)
  double floor_z;               // impassable bottom plane: needs z - R >= floor_z
  // A vertical cylindrical container (tapmc_cylinder.h), with non-periodic x and y only: the
  // centre must stay within cylinder_radius - R of the axis through (cylinder_cx, cylinder_cy).
  bool cylinder = false;
  double cylinder_cx = 0.0, cylinder_cy = 0.0, cylinder_radius = 0.0;
};

enum class PickOrder { Random, Sweep };  // Random: the paper (uniform pick); Sweep: memory order

}  // namespace tapmc

#endif
