// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix tapdilate: the tap, z -> z_floor + (z - z_floor)(1 + eps) (paper, section II).
#ifndef LMP_FIX_TAPDILATE_H
#define LMP_FIX_TAPDILATE_H

#include "fix.h"

#include <string>

namespace LAMMPS_NS {

class FixTapDilate : public Fix {
 public:
  FixTapDilate(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  double compute_scalar() override;
  double compute_vector(int) override;

 private:
  double eps_constant;      // eps when given as a number
  std::string eps_variable; // name of the equal-style variable, else empty
  int eps_var_index;
  int tap_every;            // dilate on timesteps that are multiples of tap_every
  double z_floor;
  double last_eps;          // eps of the most recent tap (thermo output)

  double current_eps();
  void schedule_next_tap();
  void check_geometry();
};

}  // namespace LAMMPS_NS

#endif
