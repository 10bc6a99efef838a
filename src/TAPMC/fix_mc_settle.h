// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle: the redeposition of the model, one complete hard-sphere Monte Carlo settling
// per timestep (paper, section II). The physics lives in tapmc_settle.{h,cpp}.
#ifndef LMP_FIX_MC_SETTLE_H
#define LMP_FIX_MC_SETTLE_H

#include "fix.h"
#include "lmptype.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tapmc {
class DomainSettle;
struct DomainSettleSetup;
class Settler;
struct SettleBox;
struct SettleResult;
struct Violation;
struct SettleParams;
}

namespace LAMMPS_NS {

class FixTapDilate;

class FixMCSettle : public Fix {
 public:
  FixMCSettle(class LAMMPS *, int, char **);
  ~FixMCSettle() override;
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void unpack_forward_comm(int, int, double *) override;

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
  bool stop_drift = false;    // 'stop drift': the windowed drift rule (tapmc_stop_rule.h)
  long drift_window = 0;      // 'window': checks averaged by 'stop drift' (kSettleDriftWindow)
  bool verify_ghosts = false; // 'verify': scheme domain checks every ghost after every round

  // per-tap diagnostics (global vector)
  double last_sweeps, last_acceptance, last_mean_z, last_hit_cap, last_trials, last_mean_z0;
  std::array<double, 6> last_parallel{};  // scheme domain: rebuilds, rounds, seconds per phase

  // gathered system, sorted by atom tag (so results do not depend on the rank count)
  std::unique_ptr<tapmc::Settler> settler;
  std::unique_ptr<tapmc::DomainSettle> domain_settle;
  std::vector<double> pack_local, pack_all;
  std::vector<int> counts, displs;
  std::vector<int> gathered_to_sorted;
  std::vector<double> xyz, radius;
  std::vector<unsigned char> movable;
  std::vector<tagint> sorted_tag;
  std::vector<int> image_shift;  // periodic wraps per sorted sphere (x, y), from the kernel
  long n_movable;

  // The run's tapdilate fixes, in definition order: the redeposition follows their taps, on
  // their tap steps only (none: every step).
  std::vector<FixTapDilate *> tappers;

  void parse_keywords(int narg, char **arg);
  tapmc::SettleParams make_params(double step, long movable) const;
  void check_walls_inside_fixed_box();
  void schedule_next_settle();
  void gather_system();
  void scatter_positions();
  double effective_d_max() const;
  void check_start_configuration();
  tapmc::SettleBox make_box() const;
  bool decomposed() const;
  tapmc::DomainSettleSetup domain_setup() const;
  double group_radius_extreme(bool largest) const;
  long count_movable() const;
  void check_start_decomposed();
  std::string violation_message(const tapmc::Violation &v, tagint tag_i, tagint tag_j) const;
  tapmc::SettleResult settle_decomposed();
  tapmc::SettleResult settle_gathered();
  void store_diagnostics(const tapmc::SettleResult &result);
};

}  // namespace LAMMPS_NS

#endif
