// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// lmp_tapmc: Debian's LAMMPS library with the TAPMC styles registered on every rank.
// Command-line compatible with `lmp` (all arguments go to the LAMMPS constructor); `-h` adds the
// TAPMC styles to LAMMPS's help.
#include "exceptions.h"
#include "input.h"
#include "lammps.h"
#include "register_styles.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

namespace {

// `-h` / `-help`: LAMMPS prints its help and ends the process (exit status 0) inside its
// constructor, before any TAPMC style is registered, and its lists of styles are compiled into
// the library. The TAPMC section is written at that exit, after LAMMPS's help, on rank 0.
bool g_help_pending = false;
bool g_rank0 = false;

bool asks_for_help(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "-help") == 0) return true;
  return false;
}

void print_tapmc_help(int status)
{
  if (!g_help_pending || !g_rank0 || status != 0) return;  // an error exit prints no help
  tapmc::print_styles_help(stdout);
  std::fflush(stdout);
}

#if defined(__GLIBC__)
void help_at_exit(int status, void *) { print_tapmc_help(status); }
#else
void help_at_exit() { print_tapmc_help(0); }
#endif

void arm_help_section(int argc, char **argv)
{
  if (!asks_for_help(argc, argv)) return;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  g_rank0 = rank == 0;
  g_help_pending = true;
#if defined(__GLIBC__)
  on_exit(&help_at_exit, nullptr);  // knows the exit status: no section after an error exit
#else
  std::atexit(&help_at_exit);
#endif
}

}  // namespace

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  // The TAPMC styles turn every error into a LAMMPS error; this is the last line of defence
  // for anything else (e.g. memory exhaustion): a message and a non-zero exit, no backtrace.
  // A LAMMPS with exceptions (always so from 2023 on; LAMMPS_EXCEPTIONS before) throws on an
  // error after printing the message: end as `lmp` does, exit status 1 and no second message.
  arm_help_section(argc, argv);
  try {
    auto *lmp = new LAMMPS_NS::LAMMPS(argc, argv, MPI_COMM_WORLD);
    g_help_pending = false;  // no help was printed: "-h" was the value of another switch
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
