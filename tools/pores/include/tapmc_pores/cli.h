// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The tapmc-pores command line as a function (the program's main() and tests call it).
#ifndef TAPMC_PORES_CLI_H
#define TAPMC_PORES_CLI_H

#include <ostream>
#include <string>
#include <vector>

namespace tapmc {
namespace pores {

// Runs tapmc-pores with `arguments` (without the program name): help on `out`, progress and
// warnings on `err`. Throws UsageError on a bad command line, and RunRefused (InputError naming
// file, frame and line, or OutputError) when the run is refused; no output file is left then.
void run_cli(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

}  // namespace pores
}  // namespace tapmc

#endif
