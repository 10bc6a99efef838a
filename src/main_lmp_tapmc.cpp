// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// lmp_tapmc: Debian's LAMMPS library with the TAPMC styles registered on every rank.
// Command-line compatible with `lmp` (all arguments go to the LAMMPS constructor).
#include "exceptions.h"
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
  // A LAMMPS with exceptions (always so from 2023 on; LAMMPS_EXCEPTIONS before) throws on an
  // error after printing the message: end as `lmp` does, exit status 1 and no second message.
  try {
    auto *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
    tapmc::register_styles(lmp);
    lmp->input->file();
    delete lmp;
  } catch (const LAMMPS_NS::LAMMPSAbortException &) {
    // error->one(): the other ranks may be waiting in a collective call
    MPI_Abort(MPI_COMM_WORLD, 1);
  } catch (const LAMMPS_NS::LAMMPSException &) {
    // error->all(): every rank is here
    MPI_Finalize();
    return 1;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "ERROR: lmp_tapmc stopped: %s\n", e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
