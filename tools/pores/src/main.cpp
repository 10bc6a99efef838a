// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// tapmc-pores: entry point; maps every kind of error to its exit code (library code never exits):
// 2 for a usage error or a refused run (bad input), as for tapmc-paper, 3 for an internal error.
#include <exception>
#include <iostream>

#include "tapmc_pores/cli.h"
#include "tapmc_pores/errors.h"

int main(int argc, char** argv) {
  using namespace tapmc::pores;
  try {
    run_cli(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
    return 0;
  } catch (const UsageError& error) {
    std::cerr << "tapmc-pores: " << error.what() << " (see tapmc-pores --help)\n";
    return 2;
  } catch (const RunRefused& error) {
    std::cerr << "tapmc-pores: error: " << error.what() << "\ntapmc-pores: no output written\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "tapmc-pores: internal error: " << error.what() << "\n";
    return 3;
  }
}
