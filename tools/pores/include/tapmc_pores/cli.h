// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The tapmc-pores command line as a function (the program's main() and tests call it).
#ifndef TAPMC_PORES_CLI_H
#define TAPMC_PORES_CLI_H

#include <ostream>
#include <string>
#include <vector>

namespace tapmc {
namespace pores {

// Runs tapmc-pores with `arguments` (without the program name). Returns the exit code:
// 0 success, 1 usage error, 2 input or analysis error (message on `err` naming file, frame, line).
int run_cli(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

}  // namespace pores
}  // namespace tapmc

#endif
