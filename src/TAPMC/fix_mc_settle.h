// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle: the redeposition of the model, one complete hard-sphere Monte Carlo settling
// per timestep (paper, section II). The physics lives in tapmc_settle.{h,cpp}.
#ifndef LMP_FIX_MC_SETTLE_H
#define LMP_FIX_MC_SETTLE_H

#include "fix.h"
#include "lammps_container.h"
#include "lmptype.h"
#include "tapmc_cylinder.h"
#include "tapmc_trial_move.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tapmc {
class DomainSettle;
struct DomainSettleSetup;
struct SettleBox;
struct SettleResult;
struct Violation;
struct SettleParams;
class Tapper;
}

namespace LAMMPS_NS {

class FixMCSettle : public Fix, public tapmc::ContainerHolder {
 public:
  FixMCSettle(class LAMMPS *, int, char **);
  ~FixMCSettle() override;
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void post_integrate() override;
  void pre_exchange() override;
  void end_of_step() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void unpack_forward_comm(int, int, double *) override;

  // tapmc::ContainerHolder: the styles of a run share one container (checked in init()).
  const std::string &container_region() const override { return container_region_id; }
  bool bed_floor(double &z0) const override
  {
    z0 = z_floor;
    return true;
  }
  bool side_walls(int dim, double &lo, double &hi) const override;
  bool keyword_radius(double &radius) const override
  {
    radius = fixed_radius;
    return fixed_radius > 0.0;
  }

 private:
  // user settings (defaults in tapmc_defaults.h)
  std::int64_t seed;
  double d_max;               // <= 0: defaults::kMaxStepOverRadius * smallest group radius
  double theta0, eta;
  long check_interval;        // trials between <Z> checks; 0 = one sweep of the group
  long max_sweeps;            // cap on sweeps per tap
  double z_floor;
  double fixed_radius;        // > 0: 'diameter' keyword given, overrides per-atom radii
  bool walls_given[2];
  double wall_pos[2][2];      // [dim][lo/hi]
  bool sweep_order;
  bool dmax_given;
  // 'scheme': gather = every rank runs the serial kernel on all spheres (results independent of
  // the rank count); domain = the decomposed redeposition (lammps_domain_settle.h); auto =
  // gather on one rank, domain on several.
  enum class Scheme { Auto, Gather, Domain } scheme;
  bool decomposed = false;    // the scheme in use: domain (true) or gather, fixed when defined
  tapmc::ThetaLaw theta_law = tapmc::ThetaLaw::Angle;  // 'theta_law' (tapmc_trial_move.h)
  // 'container REGION-ID': a vertical cylindrical container (lammps_container.h) replacing the
  // side walls; empty without one. Resolved when the fix is defined and again in init().
  std::string container_region_id;
  tapmc::Cylinder container{};
  bool stop_drift = false;    // 'stop drift': the windowed drift rule (tapmc_stop_rule.h)
  long drift_window = 0;      // 'window': checks averaged by 'stop drift' (kSettleDriftWindow)
  bool window_given = false;
  bool verify_ghosts = false; // 'verify': scheme domain checks every ghost after every round
  bool warned_idle_stop = false;  // the warning of a stop at an idle check is given once
  int taps_without_a_move = 0;    // consecutive redepositions that accepted no trial move
  bool warned_no_move = false;    // ... warned once, at kSettleNoMoveTaps
  bool warned_adrift = false;     // tapped atoms no fix mc/settle redeposits: warned once

  // per-tap diagnostics (global vector)
  double last_sweeps, last_acceptance, last_mean_z, last_hit_cap, last_trials, last_mean_z0;
  double last_idle_stop = 0.0;  // 1: stopped at a check that accepted no trial ('stop change')
  std::array<double, 6> last_parallel{};  // scheme domain: rebuilds, rounds, seconds per phase

  // How one redeposition is spread over the ranks ('scheme'), chosen once when the fix is
  // defined (the rank count is fixed by then): GatheredRedeposition or DecomposedRedeposition,
  // in fix_mc_settle.cpp.
  class Redeposition;
  class GatheredRedeposition;
  class DecomposedRedeposition;
  std::unique_ptr<Redeposition> redeposition;
  // The per-atom state of the decomposed scheme (each atom's round), which travels with the
  // atoms from the start whatever the scheme.
  std::unique_ptr<tapmc::DomainSettle> domain_settle;

  // The run's tapping fixes, in definition order: the redeposition follows their taps, on their
  // tap steps only (none: every step). Found in init(); their IDs are compared with the fixes
  // of each tap step, since a run with 'pre no' skips init() (current_tappers()).
  std::vector<tapmc::Tapper *> tappers;
  std::vector<std::string> tapper_ids;
  // Part of the bed stands still (atoms outside this fix's group or a tapping fix's group): a
  // tap can then push a sphere into one that does not follow it, so every tap is checked for
  // overlaps before its redeposition (set in init()).
  bool check_after_taps = false;
  // every atom is tapped by some tapping fix: an overlap after a tap then comes from tapping
  // fixes of different groups that dilate differently
  bool every_atom_tapped = false;
  // the run's other fixes that move atoms (other_fixes_moving_atoms()), "" if none: the
  // spheres are then checked before each tap, and an overlap found there names them
  std::string other_movers;
  bool checking_other_movers = false;

  // The settings kept in restart files (fix_mc_settle_restart.cpp: the record's layouts).
  struct RestartSetting;
  std::vector<RestartSetting> restart_settings() const;
  std::array<double *, 6> restart_diagnostics();

  void parse_keywords(int narg, char **arg);
  void warn_ignored_keywords(bool decomposed) const;
  tapmc::SettleParams make_params(double step, long movable) const;
  void resolve_side_walls();
  void check_walls_inside_fixed_box();
  void find_tappers();
  std::string other_fixes_moving_atoms() const;
  int settled_group_bits() const;
  void warn_tapped_never_redeposited(long adrift);
  void require_same_tappers();
  void schedule_next_settle(bigint after);
  double effective_d_max() const;
  tapmc::SettleBox make_box() const;
  tapmc::DomainSettleSetup domain_setup() const;
  void check_dmax_against_periods() const;
  void require_positive_radii() const;
  double group_radius_extreme(bool largest) const;
  long count_movable() const;
  std::string violation_message(const tapmc::Violation &v, tagint tag_i, tagint tag_j,
                                bool after_tap) const;
  void store_diagnostics(const tapmc::SettleResult &result);
};

}  // namespace LAMMPS_NS

#endif
