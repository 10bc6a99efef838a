// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The domain-decomposed redeposition (scheme and guarantees: lammps_domain_settle.h and
// tapmc_decomposition.h).
//
// Why it never misses an overlap: a trial of an active sphere ends inside its round's region,
// which lies within the margin e of the rank's sub-domain; any sphere it can touch lies within
// 2 R_max of that. Spheres of other ranks are ghosts when they were within the ghost cutoff
// (2 R_max + e + skin) of the sub-domain at the last borders(), and none has moved more than the
// skin since (checked after every round, a rebuild otherwise), so every sphere in reach is
// present. Those that move in the same round lie in other regions, at least 2 R_max away; the
// others are at their current positions (forward communication after every round). Along a
// periodic axis with one rank the kernel takes the nearest image of the rank's own spheres, at
// their current positions; their LAMMPS ghost copies across it, stale during a round, are left
// out.
#include "lammps_domain_settle.h"

#include "lammps_relocate.h"
#include "lammps_support.h"
#include "tapmc_defaults.h"
#include "tapmc_random.h"
#include "tapmc_stop_rule.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "neighbor.h"

#include <mpi.h>

#include <algorithm>
#include <unordered_map>
#include <cmath>
#include <numeric>

using namespace LAMMPS_NS;

namespace tapmc {

DomainSettle::DomainSettle(LAMMPS *lmp)
    : Pointers(lmp), mover_(std::make_unique<SphereMover>())
{
}

DomainSettle::~DomainSettle() = default;

double DomainSettle::ghost_cutoff(double r_max, double d_max)
{
  return 2.0 * r_max + defaults::kDomainMoveMarginOverStep * d_max +
         defaults::kDomainGhostSkinOverRadius * r_max;
}

void DomainSettle::distribute()
{
  relocate_moved_atoms(lmp, "fix mc/settle");  // remap, shrink-wrap, irregular migration
  comm->setup();
  if (neighbor->style) neighbor->setup_bins();
  comm->exchange();
  atom->nghost = 0;
  comm->borders();
}

double DomainSettle::largest_radius(const DomainSettleSetup &setup) const
{
  double r = setup.fixed_radius;
  if (r == 0.0)
    for (int i = 0; i < atom->nlocal; ++i) r = std::max(r, atom->radius[i]);
  double all = 0.0;
  MPI_Allreduce(&r, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return all;
}

// Periodic axes with a single rank along them are periodic in the kernel (nearest image, as the
// serial kernel): the rank needs no rounds along them, and LAMMPS's ghost copies of its own
// spheres across them are left out (they would be stale during a round). Along the other axes
// the periodic images are LAMMPS ghosts.
void DomainSettle::set_kernel_axes()
{
  for (int d = 0; d < 3; ++d)
    kernel_periodic_[d] = d < 2 && domain->periodicity[d] && comm->procgrid[d] == 1;
}

// The ghosts the kernel takes: one copy of each sphere per place along the axes the kernel does
// not wrap. Left out: the copies of this rank's own spheres, and repeated copies of another
// rank's sphere, across a kernel-periodic axis.
void DomainSettle::select_ghosts()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  ghost_index_.clear();
  for (int g = nlocal; g < nall; ++g) ghost_index_.push_back(g);
  if (!kernel_periodic_[0] && !kernel_periodic_[1]) return;
  double **x = atom->x;
  const tagint *tag = atom->tag;
  // Same sphere (tag) at the same place along the axes the kernel does not wrap.
  auto same_copy = [&](int a, int b) {
    if (tag[a] != tag[b]) return false;
    for (int d = 0; d < 3; ++d)
      if (!kernel_periodic_[d] && x[a][d] != x[b][d]) return false;
    return true;
  };
  auto before = [&](int a, int b) {
    if (tag[a] != tag[b]) return tag[a] < tag[b];
    for (int d = 0; d < 3; ++d)
      if (!kernel_periodic_[d] && x[a][d] != x[b][d]) return x[a][d] < x[b][d];
    return a < b;
  };
  std::sort(ghost_index_.begin(), ghost_index_.end(), before);
  ghost_index_.erase(std::unique(ghost_index_.begin(), ghost_index_.end(), same_copy),
                     ghost_index_.end());
  owned_of_tag_.clear();
  owned_of_tag_.reserve(static_cast<std::size_t>(nlocal));
  for (int i = 0; i < nlocal; ++i) owned_of_tag_.emplace(tag[i], i);
  ghost_index_.erase(std::remove_if(ghost_index_.begin(), ghost_index_.end(),
                                    [&](int g) {
                                      const auto owner = owned_of_tag_.find(tag[g]);
                                      return owner != owned_of_tag_.end() &&
                                             same_copy(g, owner->second);
                                    }),
                     ghost_index_.end());
  std::sort(ghost_index_.begin(), ghost_index_.end());  // memory order for the refreshes
}

// This rank's spheres and the selected ghosts into xyz_ / radius_ (the kernel's indices: owned
// i, then ghost k at nlocal + k), with the box the kernel sees; returns their number.
int DomainSettle::copy_spheres(const DomainSettleSetup &setup, SettleBox &box)
{
  set_kernel_axes();
  select_ghosts();
  const int nlocal = atom->nlocal;
  const int n = nlocal + static_cast<int>(ghost_index_.size());
  double **x = atom->x;
  xyz_.resize(3 * static_cast<std::size_t>(n));
  radius_.resize(n);
  for (int k = 0; k < n; ++k) {
    const int i = lammps_index(k);
    for (int d = 0; d < 3; ++d) xyz_[3 * k + d] = x[i][d];
    radius_[k] = setup.fixed_radius > 0.0 ? setup.fixed_radius : atom->radius[i];
  }
  box = setup.planes;
  for (int d = 0; d < 2; ++d) box.periodic[d] = kernel_periodic_[d];
  return n;
}

int DomainSettle::lammps_index(int k) const
{
  const int nlocal = atom->nlocal;
  return k < nlocal ? k : ghost_index_[k - nlocal];
}

// The mover takes this rank's spheres and the selected ghosts (periodicity is in the ghosts, or
// in the kernel along kernel-periodic axes); the movable owned spheres are listed in tag order,
// so the picks do not depend on LAMMPS's memory order (restarts, sorting).
void DomainSettle::load(const DomainSettleSetup &setup, double d_max, double contact_tol)
{
  const int nlocal = atom->nlocal;
  SettleBox box;
  const int n = copy_spheres(setup, box);
  mover_->reset(xyz_.data(), radius_.data(), n, box, d_max, contact_tol);
  double **x = atom->x;

  owned_by_tag_.clear();
  for (int i = 0; i < nlocal; ++i)
    if (atom->mask[i] & setup.groupbit) owned_by_tag_.push_back(i);
  const tagint *tag = atom->tag;
  std::sort(owned_by_tag_.begin(), owned_by_tag_.end(),
            [tag](int a, int b) { return tag[a] < tag[b]; });
  x_at_borders_.assign(xyz_.begin(), xyz_.begin() + 3 * static_cast<std::size_t>(nlocal));
  ghost_x_.assign(xyz_.begin() + 3 * static_cast<std::size_t>(nlocal), xyz_.end());
  // LAMMPS keeps owned coordinates unwrapped during the redeposition (its next pbc() wraps them
  // and counts the image flags): x = kernel position + (wraps since now) * L + (x - kernel x now).
  frame_.resize(2 * static_cast<std::size_t>(nlocal));
  for (int i = 0; i < nlocal; ++i)
    for (int d = 0; d < 2; ++d)
      frame_[2 * i + d] = {mover_->image_shift(i, d), x[i][d] - mover_->position(i)[d]};
  max_shift_sq_ = 0.0;
}

// Rounds from_round .. rounds-1 of this cycle get the movable spheres now in their parts, in tag
// order (LAMMPS's x holds every owned sphere's current position: publish_round copies them).
void DomainSettle::partition(const RoundSchedule &schedule, int from_round)
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  round_of_local_.resize(nlocal);
  for (int i = 0; i < nlocal; ++i) round_of_local_[i] = schedule.round_of(x[i]);
  round_members_.resize(schedule.rounds());
  for (int r = from_round; r < schedule.rounds(); ++r) round_members_[r].clear();
  for (int i : owned_by_tag_) {
    const int r = round_of_local_[i];
    if (r >= from_round) round_members_[r].push_back(i);
  }
}

// After a round: the spheres that moved to LAMMPS, their ghost copies refreshed everywhere, the
// ghosts that changed to the mover. Returns whether some sphere has moved more than the ghost
// skin since borders() (ghosts must then be rebuilt): on all ranks when `vote` (one
// non-blocking reduction, overlapped with the forward communication), else on this rank only.
bool DomainSettle::publish_round(double ghost_skin, bool vote)
{
  double **x = atom->x;
  mover_->take_moved(moved_);
  const double *length = domain->prd;
  for (int i : moved_) {
    const double *p = mover_->position(i);
    const double *b = &x_at_borders_[3 * static_cast<std::size_t>(i)];
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      double v = p[d];
      if (kernel_periodic_[d]) {
        const Frame &f = frame_[2 * static_cast<std::size_t>(i) + d];
        v += (mover_->image_shift(i, d) - f.image) * length[d] + f.offset;
      }
      x[i][d] = v;
      d2 += (v - b[d]) * (v - b[d]);
    }
    max_shift_sq_ = std::max(max_shift_sq_, d2);
  }
  int need = max_shift_sq_ > ghost_skin * ghost_skin ? 1 : 0, any = need;
  MPI_Request request;
  if (vote) MPI_Iallreduce(&need, &any, 1, MPI_INT, MPI_MAX, world, &request);
  comm->forward_comm();
  const int nlocal = atom->nlocal, ng = static_cast<int>(ghost_index_.size());
  double *known = ghost_x_.data();
  for (int k = 0; k < ng; ++k, known += 3) {
    const double *xg = x[ghost_index_[k]];
    if (xg[0] == known[0] && xg[1] == known[1] && xg[2] == known[2]) continue;
    for (int d = 0; d < 3; ++d) known[d] = xg[d];
    mover_->set_position(nlocal + k, xg);
  }
  if (vote) MPI_Wait(&request, MPI_STATUS_IGNORE);
  return any != 0;
}

std::array<DecomposedAxis, 3> DomainSettle::decomposed_axes() const
{
  std::array<DecomposedAxis, 3> axes;
  double width[3], min_width[3];
  for (int d = 0; d < 3; ++d) width[d] = domain->subhi[d] - domain->sublo[d];
  MPI_Allreduce(width, min_width, 3, MPI_DOUBLE, MPI_MIN, world);
  for (int d = 0; d < 3; ++d) {
    axes[d].split = comm->procgrid[d] > 1 || (domain->periodicity[d] && !kernel_periodic_[d]);
    axes[d].lo = domain->sublo[d];
    axes[d].hi = domain->subhi[d];
    axes[d].min_width = min_width[d];
  }
  return axes;
}

Violation DomainSettle::find_violation(const DomainSettleSetup &setup)
{
  SettleBox box;
  const int n = copy_spheres(setup, box);
  Violation v =
      Settler::find_violation(xyz_.data(), radius_.data(), n, box, defaults::kContactTolerance);
  if (v.i >= 0) v.i = lammps_index(v.i);
  if (v.j >= 0) v.j = lammps_index(v.j);
  return v;
}

namespace {
// One reduction per check: the running sums every rank adds up.
struct CheckSums {
  double sum_dz, accepted, trials, rebuild;
};
}  // namespace

// The state of one redeposition shared by its steps.
struct DomainSettle::Run {
  Run(const DomainSettleSetup &s, const SettleParams &p, long n)
      : setup(s), params(p), movable_total(n), clock(MPI_Wtime())
  {
  }
  const DomainSettleSetup &setup;
  const SettleParams &params;
  long movable_total;
  double ghost_skin = 0.0;
  std::unique_ptr<RoundSchedule> schedule;
  CounterRandom trial_stream{0, 0}, cut_stream{0, 0};
  long interval = 0;
  TrialTally tally;
  std::uint64_t next_trial = 0, cycle = 0;
  bool rebuild_pending = false;
  double clock = 0.0;
  // Adds the seconds since the last mark to a phase of the timing.
  void mark(double &phase)
  {
    const double now = MPI_Wtime();
    phase += now - clock;
    clock = now;
  }
};

// Ghosts made, the mover loaded, the rounds and the random streams set up.
void DomainSettle::prepare(Run &run)
{
  const SettleParams &params = run.params;
  distribute();
  const double r_max = largest_radius(run.setup);
  const double needed = ghost_cutoff(r_max, params.d_max);
  if (comm->get_comm_cutoff() < needed * (1.0 - 1e-12))
    error->all(FLERR, "fix mc/settle: the ghost cutoff {} is below the {} the decomposed "
               "redeposition needs (2 R_max + margin + skin, R_max = {}); set 'comm_modify "
               "cutoff {}' or larger", comm->get_comm_cutoff(), needed, r_max, needed);
  run.ghost_skin = defaults::kDomainGhostSkinOverRadius * r_max;
  load(run.setup, params.d_max, params.contact_tol);
  run.mark(timing_.rebuilds);

  const double margin = defaults::kDomainMoveMarginOverStep * params.d_max;
  guarded(lmp, "fix mc/settle", true, [&] {
    run.schedule = std::make_unique<RoundSchedule>(decomposed_axes(), 2.0 * r_max, margin);
  });
  if (!sampler_ || sampler_->d_max() != params.d_max ||
      sampler_->theta_sampler().theta0() != params.theta0)
    sampler_ = std::make_unique<TrialMoveSampler>(params.d_max, params.theta0);
  run.trial_stream = CounterRandom(params.seed, RandomPurpose::kDomainSettleMoves, params.stream)
                         .round(rank_key_index(comm->me));
  run.cut_stream = CounterRandom(params.seed, RandomPurpose::kDomainSettleCuts, params.stream);
  run.interval = Settler::trials_per_check(params.check_interval, run.movable_total);
}

// One cycle of rounds (one check interval): new cuts, then each round's trials on every rank,
// each followed by the refresh of the ghosts (and a ghost rebuild where one is due).
void DomainSettle::run_cycle(Run &run)
{
  RoundSchedule &schedule = *run.schedule;
  const std::uint64_t c = run.cycle++;
  schedule.start_cycle({run.cut_stream.uniform(3 * c), run.cut_stream.uniform(3 * c + 1),
                        run.cut_stream.uniform(3 * c + 2)});
  partition(schedule, 0);
  for (int r = 0; r < schedule.rounds(); ++r) {
    if (run.rebuild_pending) {  // collective: decided by the reduction after the last round
      distribute();
      load(run.setup, run.params.d_max, run.params.contact_tol);
      partition(schedule, r);
      ++ghost_rebuilds_;
      run.rebuild_pending = false;
      run.mark(timing_.rebuilds);
    }
    const std::vector<int> &members = round_members_[r];
    const long m = static_cast<long>(members.size());
    const long trials = round_trials(m, run.interval, run.movable_total);
    const MoveRegion region = schedule.region(r);
    long cursor = 0;
    guarded(lmp, "fix mc/settle", false, [&] {
      mover_->run(members.data(), m, run.params.order, cursor, *sampler_, run.trial_stream,
                  run.next_trial, trials, &region, run.tally);
    });
    run.next_trial += static_cast<std::uint64_t>(trials);
    ++rounds_;
    run.mark(timing_.trials);
    // The rebuild vote of the last round rides on the check's reduction.
    const bool last = r + 1 == schedule.rounds();
    run.rebuild_pending = publish_round(run.ghost_skin, !last);
    run.mark(timing_.publish);
  }
}

SettleResult DomainSettle::settle(const DomainSettleSetup &setup, const SettleParams &params,
                                  long movable_total)
{
  Settler::validate(params);
  timing_ = Timing();
  ghost_rebuilds_ = rounds_ = 0;
  Run run(setup, params, movable_total);
  prepare(run);

  // <Z> at the start, over all ranks.
  double local_height = 0.0, start_height = 0.0;
  for (int i : owned_by_tag_) local_height += mover_->position(i)[2] - setup.planes.floor_z;
  MPI_Allreduce(&local_height, &start_height, 1, MPI_DOUBLE, MPI_SUM, world);
  SettleResult result;
  result.movable = movable_total;
  result.mean_height_start = start_height / static_cast<double>(movable_total);
  ConvergenceCheck stop =
      Settler::make_convergence_check(params, movable_total, result.mean_height_start);
  double accepted_total = 0.0, trials_total = 0.0;
  for (;;) {
    const long accepted_before = run.tally.accepted, trials_before = run.tally.trials;
    run_cycle(run);
    // The <Z> check (section II): one reduction per check interval.
    const CheckSums local{run.tally.sum_dz,
                          static_cast<double>(run.tally.accepted - accepted_before),
                          static_cast<double>(run.tally.trials - trials_before),
                          run.rebuild_pending ? 1.0 : 0.0};
    CheckSums sums;
    MPI_Allreduce(&local, &sums, 4, MPI_DOUBLE, MPI_SUM, world);
    run.mark(timing_.reductions);
    run.rebuild_pending = sums.rebuild > 0.0;
    accepted_total += sums.accepted;
    trials_total += sums.trials;
    result.mean_height = (start_height + sums.sum_dz) / static_cast<double>(movable_total);
    const ConvergenceCheck::Verdict verdict = stop.after_check(
        result.mean_height, static_cast<long>(sums.accepted), static_cast<long>(sums.trials));
    if (verdict == ConvergenceCheck::Verdict::Continue) continue;
    result.hit_cap = verdict == ConvergenceCheck::Verdict::HitCap;
    break;
  }
  result.trials = static_cast<long>(trials_total);
  result.accepted = static_cast<long>(accepted_total);
  result.checks = stop.checks();
  result.list_updates = mover_->local_updates();
  return result;
}

}  // namespace tapmc
