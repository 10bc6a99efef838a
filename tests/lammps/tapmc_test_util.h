// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Helpers for library-API tests: a LAMMPS instance with the TAPMC styles, fed line by line.
#ifndef TAPMC_TEST_UTIL_H
#define TAPMC_TEST_UTIL_H

#include "input.h"
#include "lammps.h"
#include "register_styles.h"

#include <cstdlib>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace tapmc_test {

// A quiet LAMMPS instance (no screen, no log) with TAPMC registered. TAPMC_TEST_VERBOSE=1 in
// the environment keeps the screen output (LAMMPS errors end the process: this shows why).
inline std::unique_ptr<LAMMPS_NS::LAMMPS> make_lammps(MPI_Comm comm = MPI_COMM_WORLD)
{
  const char *quiet[] = {"tapmc_test", "-log", "none", "-screen", "none", "-nocite"};
  const char *verbose[] = {"tapmc_test", "-log", "none", "-nocite"};
  const bool loud = std::getenv("TAPMC_TEST_VERBOSE") != nullptr;
  auto lmp = std::make_unique<LAMMPS_NS::LAMMPS>(loud ? 4 : 6,
                                                 const_cast<char **>(loud ? verbose : quiet), comm);
  tapmc::register_styles(lmp.get());
  return lmp;
}

inline void run_lines(LAMMPS_NS::LAMMPS *lmp, const std::vector<std::string> &lines)
{
  for (const auto &line : lines) lmp->input->one(line);
}

}  // namespace tapmc_test

#endif
