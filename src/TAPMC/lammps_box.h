// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The box every TAPMC style needs, checked in one place: orthogonal, with a non-periodic z
// (a floor below, an open top above).
#ifndef TAPMC_LAMMPS_BOX_H
#define TAPMC_LAMMPS_BOX_H

#include "domain.h"
#include "error.h"
#include "lammps.h"

namespace tapmc {

// Domain::boundary[dim][side] code of a fixed ('f') face.
constexpr int kBoundaryFixed = 1;

// Stops with a message naming the style (e.g. "fix mc/settle") and what to change.
inline void require_box_with_floor(LAMMPS_NS::LAMMPS *lmp, const char *style)
{
  if (lmp->domain->triclinic)
    lmp->error->all(FLERR, "{}: triclinic boxes are not supported; use an orthogonal box", style);
  if (lmp->domain->zperiodic)
    lmp->error->all(FLERR, "{}: the z boundary is periodic; the packing needs a floor and an open "
                    "top: use e.g. 'boundary p p fm' (or 'f f fm')", style);
}

}  // namespace tapmc

#endif
