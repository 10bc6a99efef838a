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
#include "update.h"

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

// The stamp (Compute::invoked_*) of a compute whose values of this step describe the packing
// before TAPMC moved atoms: never a step, so no reader takes them as current.
constexpr LAMMPS_NS::bigint kStampBeforeTheMove = -2;

// A compute invoked earlier in this step (an eps variable that reads it, evaluated before the
// tap) holds the packing before the move, stamped with the step: LAMMPS would hand those values
// out as current (the library's extract_compute, a variable read between runs). Its stamps are
// set to kStampBeforeTheMove, so that a reader computes it again, and refresh_moved_computes
// computes it again at the end of the step.
inline void forget_computed_values(LAMMPS_NS::LAMMPS *lmp)
{
  const LAMMPS_NS::bigint step = lmp->update->ntimestep;
  for (int i = 0; i < lmp->modify->ncompute; ++i) {
    LAMMPS_NS::Compute *c = lmp->modify->compute[i];
    for (LAMMPS_NS::bigint *stamp : {&c->invoked_scalar, &c->invoked_vector, &c->invoked_array,
                                     &c->invoked_peratom, &c->invoked_local})
      if (*stamp == step) *stamp = kStampBeforeTheMove;
  }
}

// At the end of a step (ghosts and neighbour lists rebuilt): the computes forget_computed_values
// marked, and nothing computed since, are computed again, so that a variable read between runs
// (as LAMMPS allows for a compute current at the run's last step) gets the packing after the
// tap, not an error. Only computes read before the move on this step pay for it.
inline void refresh_moved_computes(LAMMPS_NS::LAMMPS *lmp)
{
  for (int i = 0; i < lmp->modify->ncompute; ++i) {
    LAMMPS_NS::Compute *c = lmp->modify->compute[i];
    if (c->invoked_scalar == kStampBeforeTheMove) c->compute_scalar();
    if (c->invoked_vector == kStampBeforeTheMove) c->compute_vector();
    if (c->invoked_array == kStampBeforeTheMove) c->compute_array();
    if (c->invoked_peratom == kStampBeforeTheMove) c->compute_peratom();
    if (c->invoked_local == kStampBeforeTheMove) c->compute_local();
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
