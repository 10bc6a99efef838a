// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Errors of the pore tool by cause; the program's main() maps each cause to its exit code.
#ifndef TAPMC_PORES_ERRORS_H
#define TAPMC_PORES_ERRORS_H

#include <sstream>
#include <stdexcept>
#include <string>

namespace tapmc {
namespace pores {

// A number as an error message shows it: six significant digits, exponent when needed ("1e+300",
// "2.5e-07"), where std::to_string's fixed notation printed 300 digits or "0.000000". (Outputs
// use number_text of json_writer.h, 12 digits.)
inline std::string message_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

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
