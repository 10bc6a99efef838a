// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The --help text of tapmc-pores (usage.cpp), apart from the command line that prints it.
#ifndef TAPMC_PORES_USAGE_H
#define TAPMC_PORES_USAGE_H

namespace tapmc {
namespace pores {

const char* usage_text();

}  // namespace pores
}  // namespace tapmc

#endif
