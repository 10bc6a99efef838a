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
// others are at their current positions (after every round, every sphere that moved in it is
// sent along LAMMPS's ghost swaps, which reach every copy of it, as a full forward
// communication would: a swap forwards what it received from an earlier one). Along a
// periodic axis with one rank the kernel takes the nearest image of the rank's own spheres, at
// their current positions; their LAMMPS ghost copies across it, stale during a round, are left
// out.
#include "lammps_domain_settle.h"

#include "lammps_compat.h"
#include "lammps_relocate.h"
#include "lammps_support.h"
#include "tapmc_defaults.h"
#include "tapmc_math.h"
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
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

using namespace LAMMPS_NS;

namespace tapmc {

DomainSettle::DomainSettle(LAMMPS *lmp, Fix *owner)
    : Pointers(lmp), mover_(std::make_unique<SphereMover>()), owner_(owner)
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

// The kernel index of each LAMMPS ghost (-1: left out), and no atom marked as moved.
void DomainSettle::index_ghosts()
{
  const int nlocal = atom->nlocal;
  kernel_of_ghost_.assign(static_cast<std::size_t>(atom->nghost), -1);
  for (std::size_t k = 0; k < ghost_index_.size(); ++k)
    kernel_of_ghost_[ghost_index_[k] - nlocal] = nlocal + static_cast<int>(k);
  fresh_.assign(static_cast<std::size_t>(nlocal + atom->nghost), 0);
  refreshed_.clear();
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
  index_ghosts();
  // rank-local data: a refusal (e.g. a dmax the fix did not see) stops with the fix's name
  guarded(lmp, "fix mc/settle", false,
          [&] { mover_->reset(xyz_.data(), radius_.data(), n, box, d_max, contact_tol); });
  double **x = atom->x;

  owned_by_tag_.clear();
  for (int i = 0; i < nlocal; ++i)
    if (atom->mask[i] & setup.groupbit) owned_by_tag_.push_back(i);
  const tagint *tag = atom->tag;
  std::sort(owned_by_tag_.begin(), owned_by_tag_.end(),
            [tag](int a, int b) { return tag[a] < tag[b]; });
  // LAMMPS keeps owned coordinates unwrapped during the redeposition (its next pbc() wraps them
  // and counts the image flags): x = kernel position + (wraps since now) * L + (x - kernel x now).
  owned_.resize(static_cast<std::size_t>(nlocal));
  for (int i = 0; i < nlocal; ++i) {
    Owned &o = owned_[i];
    for (int d = 0; d < 3; ++d) o.x_at_borders[d] = x[i][d];
    for (int d = 0; d < 2; ++d) {
      o.image[d] = mover_->image_shift(i, d);
      o.offset[d] = x[i][d] - mover_->position(i)[d];
    }
    o.tag_slot = -1;
  }
  // The movable spheres' positions in tag order too, so that the partition of every cycle reads
  // memory in order.
  tag_xyz_.resize(3 * owned_by_tag_.size());
  for (std::size_t j = 0; j < owned_by_tag_.size(); ++j) {
    const int i = owned_by_tag_[j];
    owned_[i].tag_slot = static_cast<int>(j);
    for (int d = 0; d < 3; ++d) tag_xyz_[3 * j + d] = x[i][d];
  }
  max_shift_sq_ = 0.0;
  left_home_ = false;
  const double slack = defaults::kDomainFaceSlackOverStep * d_max;
  for (int d = 0; d < 3; ++d) {
    const bool split = comm->procgrid[d] > 1;
    home_lo_[d] = split ? domain->sublo[d] - slack : -std::numeric_limits<double>::infinity();
    home_hi_[d] = split ? domain->subhi[d] + slack : std::numeric_limits<double>::infinity();
  }
}

namespace {
// Spheres (tag order) to the lists of their rounds: every list gets the sphere written at its
// end, only its own list's end advances, so the counters stay in registers (no chain of loads
// and stores through one counter when consecutive spheres share a round).
template <int Rounds>
void split_by_round(const RoundSchedule &schedule, const double *xyz, const int *sphere,
                    std::size_t m, int *round_of, int *const *out, long *size)
{
  long end[Rounds] = {};
  for (std::size_t j = 0; j < m; ++j, xyz += 3) {
    const int r = schedule.round_of(xyz);
    round_of[j] = r;
    for (int q = 0; q < Rounds; ++q) {
      out[q][end[q]] = sphere[j];
      end[q] += q == r;
    }
  }
  for (int q = 0; q < Rounds; ++q) size[q] = end[q];
}
}  // namespace

// At the start of a cycle: every movable owned sphere to the round of the part it is in, in tag
// order within each round. One branch-free pass over the positions in tag order.
void DomainSettle::partition(const RoundSchedule &schedule)
{
  const int rounds = schedule.rounds();
  const std::size_t m = owned_by_tag_.size();
  member_store_.resize(static_cast<std::size_t>(rounds) * m + 1);  // + 1: the unused writes
  tag_round_.resize(m);
  int *out[RoundSchedule::kMaxRounds];
  long size[RoundSchedule::kMaxRounds] = {};
  for (int r = 0; r < rounds; ++r) out[r] = member_store_.data() + r * m;
  const auto split = rounds == 1   ? split_by_round<1>
                     : rounds == 2 ? split_by_round<2>
                     : rounds == 4 ? split_by_round<4>
                                   : split_by_round<8>;
  split(schedule, tag_xyz_.data(), owned_by_tag_.data(), m, tag_round_.data(), out, size);
  round_size_.assign(size, size + rounds);
}

// A ghost rebuild in the middle of a cycle: each sphere keeps the round it got at the start of
// the cycle, also when it moves to another rank (the round travels with the atom through
// LAMMPS's exchange), so no sphere is active twice in a cycle or skipped. Before distribute():
void DomainSettle::hand_rounds_to_atoms()
{
  for (std::size_t j = 0; j < owned_by_tag_.size(); ++j)
    cycle_round_[owned_by_tag_[j]] = tag_round_[j];
}

// After load(): the spheres whose round is `from_round` or later, in tag order.
void DomainSettle::repartition_after_rebuild(int from_round)
{
  const int rounds = static_cast<int>(round_size_.size());
  const std::size_t m = owned_by_tag_.size();
  member_store_.resize(static_cast<std::size_t>(rounds) * m);
  tag_round_.resize(m);
  std::fill(round_size_.begin(), round_size_.end(), 0);
  for (std::size_t j = 0; j < m; ++j) {
    const int i = owned_by_tag_[j];
    const int r = cycle_round_[i];
    tag_round_[j] = r;
    if (r >= from_round && r < rounds) member_store_[r * m + round_size_[r]++] = i;
  }
}

const int *DomainSettle::members(int round) const
{
  return member_store_.data() + static_cast<std::size_t>(round) * owned_by_tag_.size();
}

// After a round: the spheres that moved to LAMMPS, their ghost copies refreshed everywhere (only
// theirs: the forward communication of the owner fix carries the moved spheres), the refreshed
// ghosts to the mover. Returns whether some sphere has moved more than the ghost skin since
// borders() or left its sub-domain by more than the face slack (ghosts must then be rebuilt and
// atoms migrate): on all ranks when `vote` (one non-blocking reduction, overlapped with the
// forward communication), else on this rank only.
bool DomainSettle::publish_round(double ghost_skin, bool vote)
{
  double **x = atom->x;
  mover_->take_moved(moved_);
  const double *length = domain->prd;
  for (const SphereMover::Moved &m : moved_) {
    const int i = m.index;
    const Owned &o = owned_[i];
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      double v = m.x[d];
      if (d < 2 && kernel_periodic_[d]) v += (m.image[d] - o.image[d]) * length[d] + o.offset[d];
      x[i][d] = v;
      d2 += (v - o.x_at_borders[d]) * (v - o.x_at_borders[d]);
    }
    max_shift_sq_ = std::max(max_shift_sq_, d2);
    for (int d = 0; d < 3; ++d)
      left_home_ = left_home_ || m.x[d] < home_lo_[d] || m.x[d] > home_hi_[d];
    fresh_[i] = 1;
    double *t = &tag_xyz_[3 * static_cast<std::size_t>(o.tag_slot)];  // moved: movable
    for (int d = 0; d < 3; ++d) t[d] = x[i][d];
  }
  int need = max_shift_sq_ > ghost_skin * ghost_skin || left_home_ ? 1 : 0, any = need;
  MPI_Request request;
  if (vote) MPI_Iallreduce(&need, &any, 1, MPI_INT, MPI_MAX, world, &request);
  compat::forward_comm_fix(comm, owner_);
  for (const SphereMover::Moved &m : moved_) fresh_[m.index] = 0;
  const int nlocal = atom->nlocal;
  for (int g : refreshed_) {
    fresh_[g] = 0;
    const int k = kernel_of_ghost_[g - nlocal];
    if (k >= 0) mover_->set_position(k, x[g]);
  }
  refreshed_.clear();
  if (verify_) verify_ghosts();
  if (vote) MPI_Wait(&request, MPI_STATUS_IGNORE);
  return any != 0;
}

int DomainSettle::pack_moved(int n, const int *list, double *buf, int pbc_flag, const int *pbc)
{
  if (n == 0) return 0;
  double shift[3] = {0.0, 0.0, 0.0};
  if (pbc_flag)
    for (int d = 0; d < 3; ++d) shift[d] = pbc[d] * domain->prd[d];
  double **x = atom->x;
  int m = 1, count = 0;
  for (int place = 0; place < n; ++place) {
    const int j = list[place];
    if (!fresh_[j]) continue;
    if (m + kForwardPerAtom > kForwardPerAtom * n) {  // nearly all moved: every position is shorter
      m = 0;
      buf[m++] = -1.0;
      for (int q = 0; q < n; ++q)
        for (int d = 0; d < 3; ++d) buf[m++] = x[list[q]][d] + shift[d];
      return m;
    }
    buf[m++] = place;
    for (int d = 0; d < 3; ++d) buf[m++] = x[j][d] + shift[d];
    ++count;
  }
  buf[0] = count;
  return m;
}

void DomainSettle::unpack_moved(int n, int first, const double *buf)
{
  if (n == 0) return;  // nothing was received: buf holds no message
  double **x = atom->x;
  const int count = static_cast<int>(buf[0]);
  const auto take = [&](int g, const double *p) {
    if (p[0] == x[g][0] && p[1] == x[g][1] && p[2] == x[g][2]) return;
    for (int d = 0; d < 3; ++d) x[g][d] = p[d];
    fresh_[g] = 1;
    refreshed_.push_back(g);
  };
  if (count < 0) {
    for (int q = 0; q < n; ++q) take(first + q, buf + 1 + 3 * q);
    return;
  }
  for (int r = 0; r < count; ++r) {
    const double *record = buf + 1 + kForwardPerAtom * r;
    take(first + static_cast<int>(record[0]), record + 1);
  }
}

// Every ghost the kernel sees must be at its owner's position (a full forward communication
// tells; the kernel holds it wrapped into the box along kernel-periodic axes); on any
// difference the run stops naming the sphere.
void DomainSettle::verify_ghosts()
{
  comm->forward_comm();
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  for (std::size_t k = 0; k < ghost_index_.size(); ++k) {
    const int g = ghost_index_[k];
    const double *seen = mover_->position(nlocal + static_cast<int>(k));
    double truth[3];
    for (int d = 0; d < 3; ++d)
      truth[d] = kernel_periodic_[d] ? wrap_periodic(x[g][d], domain->boxlo[d], domain->boxhi[d])
                                     : x[g][d];
    if (seen[0] != truth[0] || seen[1] != truth[1] || seen[2] != truth[2])
      error->one(FLERR, "fix mc/settle verify: after round {} the ghost of atom {} on rank {} "
                 "is at {} {} {} in the kernel, its owner at {} {} {}", rounds_, atom->tag[g],
                 comm->me, seen[0], seen[1], seen[2], truth[0], truth[1], truth[2]);
  }
}

// Before a round: the rounds are laid out on LAMMPS's present sub-domains, and every active
// sphere lies within the face slack of its rank's sub-domain (the kernel's coordinates equal
// LAMMPS's along split axes): else a sub-domain face could refuse its steps.
void DomainSettle::verify_round_start(const RoundSchedule &schedule, int round) const
{
  for (int d = 0; d < 3; ++d) {
    const DecomposedAxis &a = schedule.axis(d);
    if (a.split && (a.lo != domain->sublo[d] || a.hi != domain->subhi[d]))
      error->one(FLERR, "fix mc/settle verify: before round {} the rounds of rank {} are laid "
                 "out on the sub-domain [{}, {}) along {}, LAMMPS's is [{}, {})", rounds_,
                 comm->me, a.lo, a.hi, "xyz"[d], domain->sublo[d], domain->subhi[d]);
  }
  const int *active = members(round);
  for (long j = 0; j < round_size_[round]; ++j) {
    const double *p = mover_->position(active[j]);
    for (int d = 0; d < 3; ++d)
      if (p[d] < home_lo_[d] || p[d] > home_hi_[d])
        error->one(FLERR, "fix mc/settle verify: before round {} atom {} on rank {} is at {} "
                   "{} {}, beyond its sub-domain [{}, {}] along {} by more than the face slack "
                   "{} (it should have migrated)", rounds_, atom->tag[active[j]], comm->me,
                   p[0], p[1], p[2], domain->sublo[d], domain->subhi[d], "xyz"[d],
                   home_hi_[d] - domain->subhi[d]);
  }
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
  double contact = 0.0, margin = 0.0;  // of the schedule: 2 R_max and the move margin e
  std::array<double, 3> cuts_uniform{};  // this cycle's draws of the cuts
  CounterRandom trial_stream{0, 0}, cut_stream{0, 0};
  long interval = 0;
  // This cycle: the spheres of each round over all ranks (constant through a cycle, since a
  // sphere keeps its round when it migrates) and this rank's trials in each round.
  std::array<long, RoundSchedule::kMaxRounds> round_total{}, round_trials{};
  // order sweep: the tag each round's sweep reached (the next round of that index goes on from
  // the next tag in its members, whatever they are in that cycle).
  std::array<tagint, RoundSchedule::kMaxRounds> sweep_after{};
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

  run.contact = 2.0 * r_max;
  run.margin = defaults::kDomainMoveMarginOverStep * params.d_max;
  lay_out_rounds(run);
  if (!sampler_ || sampler_->d_max() != params.d_max ||
      sampler_->theta_sampler().theta0() != params.theta0 ||
      sampler_->theta_sampler().law() != params.theta_law)
    sampler_ = std::make_unique<TrialMoveSampler>(params.d_max, params.theta0, params.theta_law);
  run.trial_stream = CounterRandom(params.seed, RandomPurpose::kDomainSettleMoves, params.stream)
                         .round(sub_domain_key_index(sub_domain_number(comm->myloc, comm->procgrid)));
  run.cut_stream = CounterRandom(params.seed, RandomPurpose::kDomainSettleCuts, params.stream);
  run.interval = Settler::trials_per_check(params.check_interval, run.movable_total);
}

// The rounds laid out on the sub-domains as they are now (collective). A migration can move
// them: a shrink-wrapped box top ('m' or 's') follows the bed, which falls during the
// redeposition, and the sub-domains of a z split follow the box. Rounds laid out on the old
// sub-domains would keep the old faces as the edges of the regions, faces that atoms
// no longer cross to migrate: the bed would hang on them.
void DomainSettle::lay_out_rounds(Run &run)
{
  run.schedule = schedule_on_sub_domains(run.contact, run.margin);
}

// The rounds on the sub-domains as they are now (collective); an error naming the axis, the
// width needed and the ways out when a sub-domain is too narrow.
std::unique_ptr<RoundSchedule> DomainSettle::schedule_on_sub_domains(double contact,
                                                                     double margin)
{
  const std::array<DecomposedAxis, 3> axes = decomposed_axes();
  const bool shrink_wrapped_top = domain->boundary[2][1] >= 2;  // 's' or 'm'
  std::unique_ptr<RoundSchedule> schedule;
  guarded(lmp, "fix mc/settle", true, [&] {
    try {
      schedule = std::make_unique<RoundSchedule>(axes, contact, margin);
    } catch (const std::invalid_argument &e) {  // sub-domains too narrow for the rounds
      std::string text = std::string(e.what()) +
                         "; 'scheme gather' runs the same input on this processor grid (every "
                         "rank redeposits all spheres), or use fewer ranks along that axis";
      if (shrink_wrapped_top && comm->procgrid[2] > 1)
        text += " (the top is shrink-wrapped, so the " + std::to_string(comm->procgrid[2]) +
                " sub-domains along z share the bed's height, " +
                number(domain->boxhi[2] - domain->boxlo[2]) + " at rest: 'processors * * 1' "
                "splits x and y only)";
      throw std::invalid_argument(text);
    }
  });
  return schedule;
}

void DomainSettle::check_round_widths(const DomainSettleSetup &setup, double d_max)
{
  set_kernel_axes();
  schedule_on_sub_domains(2.0 * largest_radius(setup),
                          defaults::kDomainMoveMarginOverStep * d_max);
}

// This rank's trials in the rounds from `from_round` on (collective): the check's trials shared
// over the cycle's active spheres numbered round by round, rank by rank (round_trials), so that
// a cycle makes exactly the trials of one check. `new_cycle`: the rounds' totals are counted
// again (after a rebuild they are the cycle's, as each sphere keeps its round).
void DomainSettle::share_trials(Run &run, int from_round, bool new_cycle)
{
  const int rounds = static_cast<int>(round_size_.size());
  if (run.interval == run.movable_total) {  // one sweep a check: every active sphere once
    for (int r = from_round; r < rounds; ++r) run.round_trials[r] = round_size_[r];
    return;
  }
  long before_rank[RoundSchedule::kMaxRounds] = {};
  MPI_Exscan(round_size_.data(), before_rank, rounds, MPI_LONG, MPI_SUM, world);
  if (comm->me == 0) std::fill(before_rank, before_rank + rounds, 0L);  // Exscan leaves it
  if (new_cycle)
    MPI_Allreduce(round_size_.data(), run.round_total.data(), rounds, MPI_LONG, MPI_SUM, world);
  long cycle_total = 0;
  for (int r = 0; r < rounds; ++r) cycle_total += run.round_total[r];
  long before_round = 0;
  for (int r = 0; r < rounds; ++r) {
    if (r >= from_round)
      run.round_trials[r] = round_trials(before_round + before_rank[r], round_size_[r],
                                         run.interval, cycle_total);
    before_round += run.round_total[r];
  }
}

// One cycle of rounds (one check interval): new cuts, then each round's trials on every rank,
// each followed by the refresh of the ghosts (and a ghost rebuild where one is due).
void DomainSettle::run_cycle(Run &run)
{
  const std::uint64_t c = run.cycle++;
  run.cuts_uniform = {run.cut_stream.uniform(3 * c), run.cut_stream.uniform(3 * c + 1),
                      run.cut_stream.uniform(3 * c + 2)};
  run.schedule->start_cycle(run.cuts_uniform);
  partition(*run.schedule);
  share_trials(run, 0, true);
  for (int r = 0; r < run.schedule->rounds(); ++r) {
    if (run.rebuild_pending) {  // collective: decided by the reduction after the last round
      hand_rounds_to_atoms();
      distribute();
      load(run.setup, run.params.d_max, run.params.contact_tol);
      // the same cuts' draws on the sub-domains after the migration; each sphere keeps its round
      lay_out_rounds(run);
      run.schedule->start_cycle(run.cuts_uniform);
      repartition_after_rebuild(r);
      share_trials(run, r, false);
      ++ghost_rebuilds_;
      run.rebuild_pending = false;
      run.mark(timing_.rebuilds);
    }
    const RoundSchedule &schedule = *run.schedule;
    if (verify_) verify_round_start(schedule, r);
    const long m = round_size_[r];
    const long trials = run.round_trials[r];
    const MoveRegion region = schedule.region(r);
    const int *active = members(r);
    const tagint *tag = atom->tag;
    // order sweep: on from the tag this round's sweep reached (members are in tag order); a
    // sweep restarted every round would never reach the later tags when a round makes fewer
    // trials than it has members (check below one sweep).
    long cursor = 0;
    if (run.params.order == PickOrder::Sweep && m > 0)
      cursor = (std::upper_bound(active, active + m, run.sweep_after[r],
                                 [tag](tagint t, int i) { return t < tag[i]; }) -
                active) % m;
    guarded(lmp, "fix mc/settle", false, [&] {
      mover_->run(active, m, run.params.order, cursor, *sampler_, run.trial_stream,
                  run.next_trial, trials, &region, run.tally);
    });
    if (run.params.order == PickOrder::Sweep && m > 0 && trials > 0)
      run.sweep_after[r] = tag[active[(cursor + m - 1) % m]];
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
  result.stopped_on_idle_check = stop.stopped_on_idle_check();
  result.list_updates = mover_->local_updates();
  return result;
}

}  // namespace tapmc
