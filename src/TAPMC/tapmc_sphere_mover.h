// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The trial-move engine of the redeposition (paper, section II), LAMMPS-free and without MPI:
// n hard spheres, some of which may move, with neighbour lists kept up to date locally (only
// what moved is rebuilt). The serial kernel (Settler) runs one redeposition on it; the
// domain-decomposed fix mc/settle runs blocks of trials on each rank's own spheres, the
// others (LAMMPS ghosts) being obstacles whose positions it refreshes between blocks.
#ifndef TAPMC_SPHERE_MOVER_H
#define TAPMC_SPHERE_MOVER_H

#include "tapmc_random.h"
#include "tapmc_settle_types.h"
#include "tapmc_trial_move.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tapmc {

// A trial whose new centre leaves [lo, hi) along any axis is rejected: the sampling window of
// one round of the decomposed redeposition (tapmc_decomposition.h).
struct MoveRegion {
  double lo[3], hi[3];
};

// Running totals of blocks of trials, accumulated in place (the serial kernel adds every
// accepted dz to one running sum, in trial order).
struct TrialTally {
  long trials = 0, accepted = 0;
  double sum_dz = 0.0;  // sum of the z changes of the accepted moves
};

class SphereMover {
 public:
  SphereMover();
  ~SphereMover();
  SphereMover(const SphereMover &) = delete;
  SphereMover &operator=(const SphereMover &) = delete;

  // Takes a copy of the n spheres (xyz interleaved, radius per sphere) and builds every
  // neighbour list. box: floor, side walls and periodic axes (positions along a periodic axis
  // are wrapped into the box; image_shift counts the wraps). d_max: the largest trial step.
  // Throws std::invalid_argument for bad geometry (message names the value and its range).
  void reset(const double *xyz, const double *radius, int n, const SettleBox &box, double d_max,
             double contact_tol);

  // Sphere i (typically an obstacle: a ghost refreshed by the caller) is now at xyz[3] (finite;
  // along a periodic axis it is wrapped into the box and image_shift(i) becomes the number of
  // periods of that wrap); the lists are updated locally when it left its list skin.
  void set_position(int i, const double *xyz);

  const double *position(int i) const;   // current position (x, y, z) of sphere i
  int image_shift(int i, int axis) const;  // periods sphere i was wrapped by along x / y

  // `trials` trial moves numbered first_trial, first_trial + 1, ...: trial t draws its move
  // (and, for PickOrder::Random, its pick among candidates[0 .. m), each a sphere index in
  // [0, n), checked when the block is at least m / 2 trials) from rng at counter t
  // (TrialMoveSampler::draw_batch), so results depend only on (rng, t, candidates). Sweep order
  // visits candidates[sweep_cursor], candidates[sweep_cursor + 1], ... (cursor updated).
  // A move is accepted when the new centre stays inside `region` (if given), above the floor,
  // inside the walls and overlaps no other sphere (nearest periodic image). Adds to tally.
  void run(const int *candidates, long m, PickOrder order, long &sweep_cursor,
           const TrialMoveSampler &sampler, const CounterRandom &rng, std::uint64_t first_trial,
           long trials, const MoveRegion *region, TrialTally &tally);

  // The candidates of the run() calls to come (the same array, unchanged, until the next
  // reset()): checked and translated to internal slots here once, instead of in every block of
  // at least half a sweep (a redeposition's ~3000 checks translated the same list 3000 times:
  // 2.7 % of its instructions). Trajectories are unchanged.
  void prepare_candidates(const int *candidates, long m);

  // The spheres (caller indices) that accepted a move in run() since the previous call, each
  // once, into `moved` (cleared first), with their positions and image shifts (as position()
  // and image_shift() give them, read while the record is at hand): a caller mirroring
  // positions copies only these.
  struct Moved {
    int index;
    int image[2];
    double x[3];
  };
  void take_moved(std::vector<Moved> &moved);

  // Diagnostics: full builds and local list updates since reset; times the list rows were
  // widened (a list outgrew its row); mean list length now.
  long full_builds() const;
  long local_updates() const;
  long capacity_grows() const;
  double mean_list_length() const;

  // Self-check for tests, O(N^2): every list holds exactly the spheres in reach of the
  // reference (no duplicates, so symmetric), every sphere is within skin/2 of its reference and
  // binned in its reference's cell. Returns "" when all hold, else the first failure.
  std::string check_lists() const;

  // List skin in units of the largest radius, used from the next reset (default
  // defaults::kListSkinOverRadius). Any value > 0 gives the same moves (the lists are exact);
  // only the speed changes. Throws std::invalid_argument outside (0, +inf).
  void set_skin(double skin_over_max_radius);
  double skin() const;

  struct State;  // defined in tapmc_sphere_mover.cpp

 private:
  std::unique_ptr<State> state_;
};

}  // namespace tapmc

#endif
