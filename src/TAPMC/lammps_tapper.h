// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// What fix mc/settle needs of a fix that taps (fix tapdilate): when its tap steps fall, and its
// tap of the current step done before the redeposition, whichever of the two fixes LAMMPS calls
// first (it calls pre_exchange in the order the fixes were defined). fix mc/settle finds the
// run's tapping fixes through this interface, so a new kind of tap needs no change there.
#ifndef TAPMC_LAMMPS_TAPPER_H
#define TAPMC_LAMMPS_TAPPER_H

#include "lmptype.h"

namespace tapmc {

class Tapper {
 public:
  // The first tap step after `step`.
  virtual LAMMPS_NS::bigint next_tap_after(LAMMPS_NS::bigint step) const = 0;
  // Tap now if the current step is a tap step and this fix has not tapped on it yet: calling it
  // again, or the fix's own pre_exchange after it, does nothing more. Collective.
  virtual void tap_if_due() = 0;
  // Whether the fix was set up by a run (its tap steps scheduled): a fix defined before a run
  // with 'pre no' was not, and would never tap.
  virtual bool scheduled() const = 0;

 protected:
  ~Tapper() = default;  // never deleted through this interface: the fix owns itself
};

}  // namespace tapmc

#endif
