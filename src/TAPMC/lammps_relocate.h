// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Shared by the TAPMC fixes: bring LAMMPS back to a consistent state after owned atoms moved by
// arbitrary distances during pre_exchange() of a (forced) reneighbouring step.
#ifndef TAPMC_LAMMPS_RELOCATE_H
#define TAPMC_LAMMPS_RELOCATE_H

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "irregular.h"
#include "lammps.h"
#include "modify.h"

#include <mpi.h>
#include <string>

namespace tapmc {

// Stop with a clear message when the atom count changed (it never should: a lost atom is a bug
// or an atom pushed through a fixed boundary). One reduction.
inline void check_atom_count(LAMMPS_NS::LAMMPS *lmp, const std::string &who)
{
  LAMMPS_NS::bigint nlocal = lmp->atom->nlocal, ntotal = 0;
  MPI_Allreduce(&nlocal, &ntotal, 1, MPI_LMP_BIGINT, MPI_SUM, lmp->world);
  if (ntotal != lmp->atom->natoms)
    lmp->error->all(FLERR, "{}: atom count changed from {} to {} (atoms lost through a fixed "
                    "boundary?)", who, lmp->atom->natoms, ntotal);
}

// Every compute's values of this step are values of the packing before the move: one invoked
// earlier in the step (an eps variable that reads it, evaluated before the tap) is stamped with
// the step, and LAMMPS would hand its old values out as current (the library's
// extract_compute, a variable read between runs). Clearing the stamps makes the next reader
// compute them again.
inline void forget_computed_values(LAMMPS_NS::LAMMPS *lmp)
{
  for (int i = 0; i < lmp->modify->ncompute; ++i) {
    LAMMPS_NS::Compute *compute = lmp->modify->compute[i];
    compute->invoked_scalar = compute->invoked_vector = compute->invoked_array = -1;
    compute->invoked_peratom = compute->invoked_local = -1;
  }
}

// Wrap periodic coordinates (remap, which keeps image flags right even after long moves),
// shrink-wrap the box, and hand atoms that left more than a neighbouring sub-domain to their new
// owners (Irregular), so that Verlet's exchange / borders / neighbour build that follow on this
// step find every atom one hop from home; then check that none was lost, and forget the
// computes' values of the packing before the move. Collective.
inline void relocate_moved_atoms(LAMMPS_NS::LAMMPS *lmp, const std::string &who)
{
  auto *atom = lmp->atom;
  auto *domain = lmp->domain;
  double **x = atom->x;
  LAMMPS_NS::imageint *image = atom->image;
  for (int i = 0; i < atom->nlocal; ++i) domain->remap(x[i], image[i]);
  domain->reset_box();
  if (lmp->comm->nprocs > 1) {
    LAMMPS_NS::Irregular irregular(lmp);
    if (irregular.migrate_check()) irregular.migrate_atoms(1);
  }
  check_atom_count(lmp, who);
  forget_computed_values(lmp);
}

}  // namespace tapmc

#endif
