// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// create_packing: the initial packing by sequential gravitational deposition (Jullien-Meakin).
#ifndef TAPMC_CREATE_PACKING_H
#define TAPMC_CREATE_PACKING_H

#include "command.h"

namespace LAMMPS_NS {

// create_packing N type R seed [floor z0] [region ID] [walls x y | x | y | none]
//                [dispersity W] [density rho]
// Every rank runs the same deterministic deposition (tapmc_deposition.h) and creates the atoms
// of its own sub-domain; tags follow the deposition order. See doc/create_packing.rst.
class CreatePacking : public Command {
 public:
  CreatePacking(class LAMMPS *lmp) : Command(lmp) {}
  void command(int narg, char **arg) override;
};

}  // namespace LAMMPS_NS

#endif
