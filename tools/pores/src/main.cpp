// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// tapmc-pores: entry point; maps every exception to an exit code (library code never exits).
#include <exception>
#include <iostream>

#include "tapmc_pores/cli.h"

int main(int argc, char** argv) {
  try {
    return tapmc::pores::run_cli(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
  } catch (const std::exception& error) {
    std::cerr << "tapmc-pores: internal error: " << error.what() << "\n";
    return 3;
  }
}
