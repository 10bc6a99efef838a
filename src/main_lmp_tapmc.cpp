// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// lmp_tapmc: Debian's LAMMPS library with the TAPMC styles registered on every rank.
// Command-line compatible with `lmp` (all arguments go to the LAMMPS constructor).
#include "input.h"
#include "lammps.h"
#include "register_styles.h"

#include <mpi.h>

#include <cstdio>
#include <exception>

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  // The TAPMC styles turn every error into a LAMMPS error; this is the last line of defence
  // for anything else (e.g. memory exhaustion): a message and a non-zero exit, no backtrace.
  try {
    auto *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
    tapmc::register_styles(lmp);
    lmp->input->file();
    delete lmp;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "ERROR: lmp_tapmc stopped: %s\n", e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
