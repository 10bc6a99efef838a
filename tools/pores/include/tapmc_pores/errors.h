// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Errors of the pore tool by cause; the program's main() maps each cause to its exit code.
#ifndef TAPMC_PORES_ERRORS_H
#define TAPMC_PORES_ERRORS_H

#include <stdexcept>

namespace tapmc {
namespace pores {

// The command line is wrong (exit code 1): the message names the option and the allowed values.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The run is refused (exit code 2) and leaves no output file.
class RunRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The input cannot be analysed: the message names file, frame and line.
class InputError : public RunRefused {
 public:
  using RunRefused::RunRefused;
};

// An output file cannot be written.
class OutputError : public RunRefused {
 public:
  using RunRefused::RunRefused;
};

}  // namespace pores
}  // namespace tapmc

#endif
