// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// How every kernel refuses a parameter, written once so that all refusals use the same phrase:
// std::invalid_argument with "<name> = <value> is outside the allowed range <range>". The value
// is written the same way everywhere: a double in its shortest round-trip form (number() of
// tapmc_math.h: "-0.1" as typed, "inf", "nan"), an integer as an integer. Kernels add no
// prefix; the LAMMPS style that calls them names itself (lammps_support.h, guarded).
#ifndef TAPMC_CHECKS_H
#define TAPMC_CHECKS_H

#include "tapmc_math.h"

#include <stdexcept>
#include <string>
#include <type_traits>

namespace tapmc {

// A value as a refusal quotes it.
inline std::string value_text(double value) { return number(value); }
template <class Integer, std::enable_if_t<std::is_integral_v<Integer>, int> = 0>
std::string value_text(Integer value)
{
  return std::to_string(value);
}

// The phrase itself, for a value already in text (a style quoting the argument as typed).
inline std::string outside_range_message(const std::string &name, const std::string &value,
                                         const std::string &range)
{
  return name + " = " + value + " is outside the allowed range " + range;
}

// Throws std::invalid_argument for `name` = `value`, which is outside `range` (written in
// interval notation, e.g. "(0, +inf)", "[0, 1)", "(finite)", with a short reason after it in
// parentheses where the range alone does not explain itself). Called only after the test
// fails, so a check in a loop builds no string.
template <class Value>
[[noreturn]] void throw_outside_range(const std::string &name, Value value,
                                      const std::string &range)
{
  throw std::invalid_argument(outside_range_message(name, value_text(value), range));
}

}  // namespace tapmc

#endif
