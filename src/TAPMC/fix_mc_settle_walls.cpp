// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle's side walls and the box its kernels see: 'xwalls'/'ywalls' or the fixed box
// faces, checked against the box, read live for the run's one-container check
// (lammps_container.h), and the planes and cylinder handed to the kernels (tapmc_settle.h).
// fix_mc_settle.cpp runs the redeposition.
#include "fix_mc_settle.h"

#include "lammps_box.h"
#include "tapmc_settle.h"

#include "domain.h"
#include "error.h"

using namespace LAMMPS_NS;

// Side walls given with 'xwalls'/'ywalls' along a fixed ('f') boundary must lie within the box
// faces: spheres pushed beyond a face would be lost by LAMMPS.
void FixMCSettle::check_walls_inside_fixed_box()
{
  for (int dim = 0; dim < 2; ++dim) {
    if (!walls_given[dim] || domain->periodicity[dim]) continue;
    for (int side = 0; side < 2; ++side) {
      if (domain->boundary[dim][side] != tapmc::kBoundaryFixed) continue;
      const double lo = domain->boxlo[dim], hi = domain->boxhi[dim];
      const double w = wall_pos[dim][side];
      if (w < lo || w > hi)
        error->all(FLERR, "fix mc/settle: {}walls {} = {} is outside the box: along a fixed ('f') "
                   "{} boundary the side walls must lie within the box faces [{}, {}]",
                   "xy"[dim], side == 0 ? "lo" : "hi", w, "xy"[dim], lo, hi);
    }
  }
}

// The walls as they are now: 'xwalls'/'ywalls', else the box faces read live (another fix
// mc/settle of the run may compare before its own init() has re-read the faces after a
// change_box).
bool FixMCSettle::side_walls(int dim, double &lo, double &hi) const
{
  if (dim < 0 || dim > 1 || domain->periodicity[dim] || !container_region_id.empty())
    return false;
  lo = walls_given[dim] ? wall_pos[dim][0] : domain->boxlo[dim];
  hi = walls_given[dim] ? wall_pos[dim][1] : domain->boxhi[dim];
  return true;
}

// The side walls of the box as it is now: 'xwalls'/'ywalls' where given, else the faces of a
// fixed ('f') boundary; none along a periodic side or in a container. From the constructor and
// from init(), since change_box may move the faces or change the boundary between runs.
void FixMCSettle::resolve_side_walls()
{
  for (int dim = 0; dim < 2; ++dim) {
    if (domain->periodicity[dim] || !container_region_id.empty()) {
      if (walls_given[dim])
        error->all(FLERR, "fix mc/settle: {}walls given but the {} boundary is periodic; side "
                   "walls exist only in non-periodic directions", "xy"[dim], "xy"[dim]);
      continue;
    }
    if (walls_given[dim]) continue;
    if (domain->boundary[dim][0] != tapmc::kBoundaryFixed ||
        domain->boundary[dim][1] != tapmc::kBoundaryFixed)
      error->all(FLERR, "fix mc/settle: the {0} boundary is shrink-wrapped, so the side walls "
                 "have no fixed position; use 'boundary f' in {0} or give '{0}walls lo hi'",
                 "xy"[dim]);
    wall_pos[dim][0] = domain->boxlo[dim];
    wall_pos[dim][1] = domain->boxhi[dim];
  }
  check_walls_inside_fixed_box();
}

tapmc::SettleBox FixMCSettle::make_box() const
{
  tapmc::SettleBox box{};
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = domain->boxlo[d];
    box.hi[d] = domain->boxhi[d];
  }
  for (int dim = 0; dim < 2; ++dim) {
    box.periodic[dim] = domain->periodicity[dim] != 0;
    box.wall_lo[dim] = box.wall_hi[dim] = !box.periodic[dim] && container_region_id.empty();
    box.wall_lo_pos[dim] = wall_pos[dim][0];
    box.wall_hi_pos[dim] = wall_pos[dim][1];
  }
  box.floor_z = z_floor;
  if (!container_region_id.empty()) {
    box.cylinder = true;
    box.cylinder_cx = container.cx;
    box.cylinder_cy = container.cy;
    box.cylinder_radius = container.radius;
  }
  return box;
}
