// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// lmp_tapmc: Debian's LAMMPS library with the TAPMC styles registered on every rank.
// Command-line compatible with `lmp` (all arguments go to the LAMMPS constructor).
#include "input.h"
#include "lammps.h"
#include "register_styles.h"

#include <mpi.h>

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  auto *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
  tapmc::register_styles(lmp);
  lmp->input->file();
  delete lmp;
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
