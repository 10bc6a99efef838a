// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The domain-decomposed redeposition behind fix mc/settle (scheme 'domain'): each rank moves
// only the spheres it owns, seeing its neighbours' as LAMMPS ghosts, in the rounds of
// tapmc_decomposition.h. Between rounds the moved ghosts are refreshed: a forward communication
// through LAMMPS's ghost swaps that carries only the spheres that moved in the round;
// when any sphere has moved more than the ghost skin since the ghosts were made, atoms migrate
// and ghosts are rebuilt (exchange and borders). The <Z> check is one global reduction per check
// interval. Memory per rank: its own spheres and their ghosts, O(N / ranks).
#ifndef TAPMC_LAMMPS_DOMAIN_SETTLE_H
#define TAPMC_LAMMPS_DOMAIN_SETTLE_H

#include "lmptype.h"
#include "pointers.h"

#include "tapmc_decomposition.h"
#include "tapmc_settle.h"
#include "tapmc_sphere_mover.h"

#include <memory>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {
class Fix;
}

namespace tapmc {

struct DomainSettleSetup {
  int groupbit = 0;           // the movable group
  double fixed_radius = 0.0;  // > 0: every sphere has this radius (the 'diameter' keyword)
  SettleBox planes{};         // floor and side walls (the periodic flags are ignored: ghosts)
};

class DomainSettle : protected LAMMPS_NS::Pointers {
 public:
  // owner: the fix whose forward communication carries the moved spheres; its comm_forward must
  // be at least kForwardPerAtom, and its pack/unpack_forward_comm call pack_moved/unpack_moved.
  DomainSettle(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::Fix *owner);
  ~DomainSettle();

  // Doubles per atom of the moved-sphere message: (place in the swap's list, x, y, z).
  static constexpr int kForwardPerAtom = 4;
  // One swap of the moved-sphere forward communication: the spheres of `list` that changed
  // position in this round (a count, then one record each; or -1 then every position when that
  // is shorter), shifted by the swap's periodic image; at most kForwardPerAtom * n doubles.
  int pack_moved(int n, const int *list, double *buf, int pbc_flag, const int *pbc);
  void unpack_moved(int n, int first, const double *buf);

  // After every round, also compare each ghost the kernel sees with its owner's position (a full
  // forward communication), and before every round check that each active sphere lies within
  // the face slack of this rank's sub-domain (no sub-domain face can refuse its next step); stop
  // with an error on any difference: checks of the scheme, for tests and debugging ('verify
  // yes' of fix mc/settle).
  void set_verify(bool on) { verify_ = on; }

  // Per-atom state that travels with the atoms when they migrate (the owner fix's grow_arrays,
  // copy_arrays, pack_exchange and unpack_exchange call these): the round of the current cycle
  // in which the sphere is active.
  void grow_atoms(int nmax) { cycle_round_.resize(static_cast<std::size_t>(nmax), -1); }
  void copy_atom(int from, int to) { cycle_round_[to] = cycle_round_[from]; }
  int pack_atom(int i, double *buf) const
  {
    buf[0] = cycle_round_[i];
    return 1;
  }
  int unpack_atom(int i, const double *buf)
  {
    cycle_round_[i] = static_cast<int>(buf[0]);
    return 1;
  }

  // Ghost cutoff the scheme needs: a contact (2 R_max), the move margin and the ghost skin.
  static double ghost_cutoff(double r_max, double d_max);

  // Collective. Atoms to their owners (after the tap moved them by any distance), ghosts made.
  void distribute();

  // Collective, after distribute(): the first overlap or plane violation among this rank's
  // spheres and ghosts, i == -1 when none (indices are local LAMMPS indices).
  Violation find_violation(const DomainSettleSetup &setup);
  // Collective, after distribute(), on the bed at rest (a run's setup): an error naming the axis
  // and the width needed when a sub-domain is too narrow for the rounds, as every redeposition
  // checks. With a shrink-wrapped top the sub-domains of a z split follow the bed: a bed too
  // short for them passes the tapped (dilated) box of the first redeposition and fails in a
  // later one, at a ghost rebuild; checked at setup, it stops before the first tap.
  void check_round_widths(const DomainSettleSetup &setup, double d_max);

  // Collective: one complete redeposition (paper, section II) of the group's spheres; the
  // atoms end where LAMMPS's own exchange and borders (which follow on this step) expect them.
  // movable_total: spheres in the group over all ranks.
  SettleResult settle(const DomainSettleSetup &setup, const SettleParams &params,
                      long movable_total);

  // Diagnostics of the last settle() on this rank: ghost rebuilds (exchange + borders) during
  // it, rounds, and wall-clock seconds in each phase.
  struct Timing {
    double trials = 0;      // the kernel's trial moves
    double publish = 0;     // moved spheres to LAMMPS, forward communication and rebuild vote,
                            // ghosts to the kernel
    double reductions = 0;  // the per-check <Z> reduction
    double rebuilds = 0;    // migration and ghost rebuilds (exchange, borders, kernel reset)
  };
  long ghost_rebuilds() const { return ghost_rebuilds_; }
  long rounds() const { return rounds_; }
  const Timing &timing() const { return timing_; }

 private:
  std::unique_ptr<SphereMover> mover_;
  std::unique_ptr<TrialMoveSampler> sampler_;
  std::vector<double> xyz_, radius_;
  std::vector<SphereMover::Moved> moved_;  // spheres moved in the last round
  std::vector<int> ghost_index_;         // LAMMPS index of the kernel's ghost k (index nlocal + k)
  std::vector<int> kernel_of_ghost_;     // per LAMMPS ghost (index - nlocal): kernel index or -1
  std::vector<unsigned char> fresh_;     // per LAMMPS atom: position changed in this round
  std::vector<int> refreshed_;           // ghosts the round's forward communication updated
  LAMMPS_NS::Fix *owner_;
  bool verify_ = false;
  bool kernel_periodic_[3] = {false, false, false};  // periodic in the kernel (set_kernel_axes)
  std::unordered_map<LAMMPS_NS::tagint, int> owned_of_tag_;
  // What publish_round needs of an owned sphere that moved, in one record.
  struct Owned {
    double x_at_borders[3];  // LAMMPS position at load()
    double offset[2];        // x, y: LAMMPS coordinate - kernel coordinate at load()
    int image[2];            // x, y: the kernel's wrap count at load()
    int tag_slot;            // place in owned_by_tag_, or -1 (not movable)
  };
  std::vector<Owned> owned_;  // per owned LAMMPS atom
  std::vector<int> owned_by_tag_;               // movable owned spheres, in tag order
  // The active spheres of each round of the cycle, in tag order: round r's are the first
  // round_size_[r] entries of member_store_ from r * (movable owned spheres).
  std::vector<int> member_store_;
  std::vector<long> round_size_;
  std::vector<int> cycle_round_;  // per LAMMPS atom: its round in this cycle (travels with it)
  std::vector<double> tag_xyz_;   // positions of owned_by_tag_, in that order
  std::vector<int> tag_round_;    // rounds of owned_by_tag_ in this cycle
  long ghost_rebuilds_ = 0, rounds_ = 0;
  Timing timing_;
  double max_shift_sq_ = 0.0;  // largest squared displacement of an owned sphere since borders
  // This rank's sub-domain widened by the face slack (kDomainFaceSlackOverStep d_max) along the
  // split axes, unbounded along the others: an owned sphere beyond it must migrate.
  double home_lo_[3] = {0, 0, 0}, home_hi_[3] = {0, 0, 0};
  bool left_home_ = false;  // an owned sphere moved beyond home_lo_ / home_hi_ since borders

  struct Run;
  void prepare(Run &run);
  void run_cycle(Run &run);
  void lay_out_rounds(Run &run);
  std::unique_ptr<RoundSchedule> schedule_on_sub_domains(double contact, double margin);
  void set_kernel_axes();
  void select_ghosts();
  void index_ghosts();
  int copy_spheres(const DomainSettleSetup &setup, SettleBox &box);
  int lammps_index(int kernel_index) const;
  void load(const DomainSettleSetup &setup, double d_max, double contact_tol);
  void partition(const RoundSchedule &schedule);
  void hand_rounds_to_atoms();
  void repartition_after_rebuild(int from_round);
  void share_trials(Run &run, int from_round, bool new_cycle);
  const int *members(int round) const;
  bool publish_round(double ghost_skin, bool vote);
  void verify_ghosts();
  void verify_round_start(const RoundSchedule &schedule, int round) const;
  std::array<DecomposedAxis, 3> decomposed_axes() const;
  double largest_radius(const DomainSettleSetup &setup) const;
};

}  // namespace tapmc

#endif
