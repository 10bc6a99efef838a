// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix tapdilate: the tap, z -> z_floor + (z - z_floor)(1 + eps) (paper, section II).
#ifndef LMP_FIX_TAPDILATE_H
#define LMP_FIX_TAPDILATE_H

#include "fix.h"
#include "lammps_container.h"
#include "lammps_tapper.h"
#include "lmptype.h"
#include "tapmc_dilation.h"

#include <string>

namespace LAMMPS_NS {

class FixTapDilate : public Fix, public tapmc::Tapper, public tapmc::ContainerHolder {
 public:
  FixTapDilate(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void post_integrate() override;
  void pre_exchange() override;
  void end_of_step() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // tapmc::Tapper, for fix mc/settle (taps fall on the multiples of 'every').
  void tap_if_due() override;
  bool scheduled() const override { return next_reneighbor >= 0; }
  bigint next_tap_after(bigint step) const override;
  // tapmc::ContainerHolder, for fix mc/settle's check of one container per run.
  const std::string &container_region() const override { return container_region_id; }
  bool bed_floor(double &z0) const override
  {
    z0 = params.z_floor;
    return true;
  }

 private:
  tapmc::DilationParams params;  // eps (when given as a number), every, floor
  std::string eps_variable; // name of the equal-style variable, else empty
  int eps_var_index;
  double last_eps;          // eps of the most recent tap (outputs; kept in restart files)
  bigint tapped_step;       // timestep of the most recent tap (-1: none yet)
  // z beyond which a double cannot resolve the contacts of the smallest spheres (init(); +inf
  // without radii): a tap lifting a sphere beyond it stops the run by name
  double exact_z_bound = std::numeric_limits<double>::infinity();
  // 'container REGION-ID', or empty. The tap moves spheres along z only, so a sphere inside a
  // vertical cylinder stays inside: the container changes no tap, it is resolved (at
  // definition and in init()) to check it as the other styles do and to compare it with theirs.
  std::string container_region_id;

  double current_eps();
  bool tapped_this_step() const;  // this fix tapped on the current step (also with eps = 0)
  void schedule_next_tap();
  void check_geometry();
  void resolve_container(double max_sphere_radius);
};

}  // namespace LAMMPS_NS

#endif
