// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix mc/settle: runs one complete redeposition per tap step and puts the atoms back where LAMMPS
// expects them. Two schemes (keyword 'scheme'):
// - gather: every rank gathers all spheres sorted by tag and runs the same deterministic serial
//   kernel (tapmc_settle.h), then keeps its own atoms: identical results for any rank count.
// - domain: each rank moves its own spheres against LAMMPS ghosts (lammps_domain_settle.h):
//   memory and work O(N / ranks); results depend on the processor grid (deterministic for a
//   fixed grid and seed), the physics does not.
#include "fix_mc_settle.h"

#include "lammps_box.h"
#include "lammps_citation.h"
#include "lammps_compat.h"
#include "lammps_container.h"
#include "lammps_domain_settle.h"
#include "lammps_keywords.h"
#include "lammps_relocate.h"
#include "lammps_support.h"
#include "lammps_tapper.h"
#include "tapmc_contact.h"
#include "tapmc_defaults.h"
#include "tapmc_settle.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
constexpr int kPackedPerAtom = 6;  // tag, x, y, z, radius, movable
constexpr int kVectorSize = 13;
const char *const kAxisName[2] = {"x", "y"};
}  // namespace

// One complete redeposition per tap step, spread over the ranks as the 'scheme' keyword says.
class FixMCSettle::Redeposition {
 public:
  // The schemes derive from this and from LAMMPS's Pointers, whose destructor is noexcept in
  // 2021 and noexcept(false) from 2023 on; both bases must promise the same, in either version.
  virtual ~Redeposition() noexcept(std::is_nothrow_destructible_v<LAMMPS_NS::Pointers>) = default;
  // From init(): the depth of the ghost shell the scheme reads, given the largest radius of all
  // spheres (collective).
  virtual double ghost_depth(double r_max) = 0;
  // From setup (and after every tap when part of the bed stands still: `after_tap`): stops with
  // an error naming the atoms when the configuration has an overlap or a sphere through the
  // floor or a wall (collective).
  virtual void check_start(bool after_tap) = 0;
  // One redeposition; the atoms end where LAMMPS's exchange and borders of this step expect
  // them (collective).
  virtual tapmc::SettleResult settle() = 0;
  // Output vector [7]-[12] after settle(): zeros unless the scheme is decomposed.
  virtual std::array<double, 6> parallel_diagnostics() const { return {}; }
};

// 'scheme gather': every rank gathers all spheres sorted by tag, runs the same deterministic
// serial kernel (tapmc_settle.h) and keeps its own atoms: the same trajectory on any rank count.
class FixMCSettle::GatheredRedeposition : public FixMCSettle::Redeposition,
                                          protected LAMMPS_NS::Pointers {
 public:
  explicit GatheredRedeposition(FixMCSettle &fix) :
      Pointers(fix.lmp), fix(fix), settler(std::make_unique<tapmc::Settler>())
  {
  }
  double ghost_depth(double r_max) override { return 2.0 * r_max; }  // one contact
  void check_start(bool after_tap) override;
  tapmc::SettleResult settle() override;

 private:
  FixMCSettle &fix;
  std::unique_ptr<tapmc::Settler> settler;
  // the gathered system, sorted by atom tag (so results do not depend on the rank count)
  std::vector<double> pack_local, pack_all;
  std::vector<int> counts, displs;
  std::vector<int> gathered_to_sorted;
  std::vector<double> xyz, radius;
  std::vector<unsigned char> movable;
  std::vector<tagint> sorted_tag;
  std::vector<int> image_shift;  // periodic wraps per sorted sphere (x, y), from the kernel
  long n_movable = 0;

  void gather_system();
  void scatter_positions();
};

// 'scheme domain': each rank moves its own spheres against LAMMPS ghosts
// (lammps_domain_settle.h): memory and work O(N / ranks).
class FixMCSettle::DecomposedRedeposition : public FixMCSettle::Redeposition,
                                            protected LAMMPS_NS::Pointers {
 public:
  explicit DecomposedRedeposition(FixMCSettle &fix) : Pointers(fix.lmp), fix(fix) {}
  double ghost_depth(double r_max) override;
  void check_start(bool after_tap) override;
  tapmc::SettleResult settle() override;
  std::array<double, 6> parallel_diagnostics() const override;

 private:
  FixMCSettle &fix;
  tapmc::DomainSettle &kernel() const { return *fix.domain_settle; }
};

FixMCSettle::FixMCSettle(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), seed(0), d_max(0.0), theta0(tapmc::defaults::kThetaWidth),
    eta(tapmc::defaults::kSettleEta), check_interval(0),
    max_sweeps(tapmc::defaults::kSettleMaxSweeps), z_floor(domain->boxlo[2]), fixed_radius(0.0),
    walls_given{false, false}, wall_pos{{0, 0}, {0, 0}}, sweep_order(false), dmax_given(false),
    scheme(Scheme::Auto), last_sweeps(0),
    last_acceptance(0), last_mean_z(0), last_hit_cap(0), last_trials(0), last_mean_z0(0)
{
  tapmc::cite_paper(lmp);
  if (narg < 4)
    error->all(FLERR, "fix mc/settle: expected 'fix ID group mc/settle seed [keyword value ...]',"
               " got {} argument(s)", narg);
  seed = tapmc::parse_seed(lmp, "fix mc/settle", "seed", arg[3]);
  drift_window = tapmc::defaults::kSettleDriftWindow;

  parse_keywords(narg, arg);
  // The kernel's one validation; without 'dmax' the step comes from the radii at each tap
  // (kMaxStepOverRadius times the smallest radius, > 0 once the radii are checked). Movable 0:
  // the group's size, which the cap of 'check' against 'maxsweeps' needs, is known at each tap,
  // where make_params checks it.
  const double step = dmax_given ? d_max : tapmc::defaults::kMaxStepOverRadius;
  tapmc::guarded(lmp, "fix mc/settle", true,
                 [&] { tapmc::Settler::validate(make_params(step, 0)); });

  tapmc::require_box_with_floor(lmp, "fix mc/settle");
  if (!container_region_id.empty()) {
    // the cylinder replaces the side walls: x and y not periodic (checked by the resolution),
    // no flat walls inside the box
    if (walls_given[0] || walls_given[1])
      error->all(FLERR, "fix mc/settle: {}walls and container {} both given; a container "
                 "replaces the side walls: give one of them", walls_given[0] ? "x" : "y",
                 container_region_id);
    container = tapmc::resolve_container(lmp, "fix mc/settle", container_region_id, 0.0);
  }
  resolve_side_walls();
  check_dmax_against_periods();
  if (fixed_radius == 0.0 && !atom->radius_flag)
    error->all(FLERR, "fix mc/settle: the atom style has no radius; use atom_style sphere or the "
               "'diameter' keyword");

  force_reneighbor = 1;
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = kVectorSize;
  extvector = 0;
  global_freq = 1;
  restart_global = 1;
  // The decomposed scheme: moved spheres between rounds (forward communication), and each
  // atom's round of the cycle travels with it when it migrates.
  domain_settle = std::make_unique<tapmc::DomainSettle>(lmp, this);
  comm_forward = tapmc::DomainSettle::kForwardPerAtom;
  maxexchange = 1;
  atom->add_callback(Atom::GROW);
  FixMCSettle::grow_arrays(atom->nmax);

  decomposed = scheme == Scheme::Domain || (scheme == Scheme::Auto && comm->nprocs > 1);
  if (decomposed)
    redeposition = std::make_unique<DecomposedRedeposition>(*this);
  else
    redeposition = std::make_unique<GatheredRedeposition>(*this);
  warn_ignored_keywords(decomposed);
}

// Keywords that a combination of settings makes meaningless are accepted, but said to be.
void FixMCSettle::warn_ignored_keywords(bool decomposed) const
{
  if (comm->me != 0) return;
  if (window_given && !stop_drift)
    error->warning(FLERR, "fix mc/settle: window = {} is ignored with 'stop change' (the "
                   "default); it sets the checks averaged by 'stop drift'", drift_window);
  if (verify_ghosts && !decomposed)
    error->warning(FLERR, "fix mc/settle: verify yes is ignored with scheme gather{}; it checks "
                   "the ghosts of scheme domain", scheme == Scheme::Auto ? " (scheme auto on one "
                   "rank)" : "");
}

void FixMCSettle::grow_arrays(int nmax)
{
  domain_settle->grow_atoms(nmax);
}

void FixMCSettle::copy_arrays(int i, int j, int /*delflag*/)
{
  domain_settle->copy_atom(i, j);
}

int FixMCSettle::pack_exchange(int i, double *buf)
{
  return domain_settle->pack_atom(i, buf);
}

int FixMCSettle::unpack_exchange(int nlocal, double *buf)
{
  return domain_settle->unpack_atom(nlocal, buf);
}

int FixMCSettle::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  return domain_settle->pack_moved(n, list, buf, pbc_flag, pbc);
}

void FixMCSettle::unpack_forward_comm(int n, int first, double *buf)
{
  domain_settle->unpack_moved(n, first, buf);
}

FixMCSettle::~FixMCSettle()
{
  atom->delete_callback(id, Atom::GROW);
}

// One table of keywords: name, number of values, what the values set. Ranges are checked once,
// by the kernel (Settler::validate), after all keywords are read.
void FixMCSettle::parse_keywords(int narg, char **arg)
{
  using tapmc::Keyword;
  auto number = [&](const char *name, const char *text) {
    return tapmc::parse_real(lmp, "fix mc/settle", name, text);
  };
  auto integer = [&](const char *name, const char *text) {
    return tapmc::parse_long(lmp, "fix mc/settle", name, text);
  };
  auto walls = [&](int dim) {
    return [this, dim, number](char **v) {
      const std::string name = std::string(kAxisName[dim]) + "walls";
      wall_pos[dim][0] = number((name + " lo").c_str(), v[0]);
      wall_pos[dim][1] = number((name + " hi").c_str(), v[1]);
      if (!(wall_pos[dim][0] < wall_pos[dim][1]))
        error->all(FLERR, "fix mc/settle: {}walls lo = {} must be below hi = {}", kAxisName[dim],
                   v[0], v[1]);
      walls_given[dim] = true;
    };
  };
  const Keyword table[] = {
      {"dmax", 1,
       [&](char **v) {
         d_max = number("dmax", v[0]);
         dmax_given = true;
       }},
      {"theta0", 1, [&](char **v) { theta0 = number("theta0", v[0]); }},
      {"theta_law", 1,
       [&](char **v) {
         const std::string law = v[0];
         if (law == "angle")
           theta_law = tapmc::ThetaLaw::Angle;
         else if (law == "solid")
           theta_law = tapmc::ThetaLaw::Solid;
         else if (law == "exponential")
           theta_law = tapmc::ThetaLaw::Exponential;
         else if (law == "linear")
           theta_law = tapmc::ThetaLaw::Linear;
         else
           error->all(FLERR, "fix mc/settle: theta_law = {} must be 'angle' (P(theta) of eq. 1 "
                      "per unit angle, the default), 'solid' (per unit solid angle), "
                      "'exponential' or 'linear' (section II's alternative laws)", law);
       }},
      {"eta", 1, [&](char **v) { eta = number("eta", v[0]); }},
      {"check", 1, [&](char **v) { check_interval = integer("check", v[0]); }},
      {"maxsweeps", 1, [&](char **v) { max_sweeps = integer("maxsweeps", v[0]); }},
      {"floor", 1, [&](char **v) { z_floor = number("floor", v[0]); }},
      {"diameter", 1,
       [&](char **v) {
         const double d = number("diameter", v[0]);
         if (!(d > 0.0))
           error->all(FLERR, "fix mc/settle: {}",
                      tapmc::outside_range_message("diameter", v[0], "(0, +inf)"));
         fixed_radius = 0.5 * d;
       }},
      {"xwalls", 2, walls(0)},
      {"ywalls", 2, walls(1)},
      {"order", 1,
       [&](char **v) {
         const std::string order = v[0];
         if (order != "random" && order != "sweep")
           error->all(FLERR, "fix mc/settle: order = {} must be 'random' (the paper) or 'sweep'",
                      order);
         sweep_order = order == "sweep";
       }},
      {"scheme", 1,
       [&](char **v) {
         const std::string name = v[0];
         if (name != "auto" && name != "gather" && name != "domain")
           error->all(FLERR, "fix mc/settle: scheme = {} must be 'auto' (gather on one rank, "
                      "domain on several), 'gather' or 'domain'", name);
         scheme = name == "gather" ? Scheme::Gather
                                   : (name == "domain" ? Scheme::Domain : Scheme::Auto);
       }},
      {"stop", 1,
       [&](char **v) {
         const std::string rule = v[0];
         if (rule != "change" && rule != "drift")
           error->all(FLERR, "fix mc/settle: stop = {} must be 'change' (the paper's rule) or "
                      "'drift'", rule);
         stop_drift = rule == "drift";
       }},
      {"window", 1,
       [&](char **v) {
         drift_window = integer("window", v[0]);
         window_given = true;
       }},
      {tapmc::kContainerKeyword, 1, [&](char **v) { container_region_id = v[0]; }},
      {"verify", 1,
       [&](char **v) {
         const std::string value = v[0];
         if (value != "yes" && value != "no")
           error->all(FLERR, "fix mc/settle: verify = {} must be 'yes' or 'no'", value);
         verify_ghosts = value == "yes";
       }},
  };
  tapmc::parse_keywords(lmp, "fix mc/settle", table, 4, narg, arg);
}

// The kernel's parameters for a redeposition with step bound `step` of `movable` spheres.
tapmc::SettleParams FixMCSettle::make_params(double step, long movable) const
{
  tapmc::SettleParams params;
  params.d_max = step;
  params.theta0 = theta0;
  params.theta_law = theta_law;
  params.eta = eta;
  params.check_interval = check_interval;
  // Refused when check exceeds the cap (the movable count, hence the cap, may have changed
  // since the run started, e.g. by delete_atoms): a LAMMPS error on every rank (same counts).
  tapmc::guarded(lmp, "fix mc/settle", true, [&] {
    params.max_checks = tapmc::Settler::max_checks_for_sweeps(max_sweeps, check_interval, movable);
  });
  params.contact_tol = tapmc::defaults::kContactTolerance;
  params.seed = static_cast<std::uint64_t>(seed);
  params.stream = static_cast<std::uint64_t>(update->ntimestep);
  params.order = sweep_order ? tapmc::PickOrder::Sweep : tapmc::PickOrder::Random;
  params.stop = stop_drift ? tapmc::StopRule::Drift : tapmc::StopRule::Change;
  params.drift_window = drift_window;
  return params;
}

int FixMCSettle::setmask()
{
  return PRE_EXCHANGE | POST_INTEGRATE | END_OF_STEP;
}

// Computes read before this step's move (an eps variable's) computed again for the packing
// after it (lammps_relocate.h): one loop over the computes per step.
void FixMCSettle::end_of_step()
{
  tapmc::refresh_moved_computes(lmp);
}

void FixMCSettle::init()
{
  tapmc::quiet_sorting_without_pair_style(lmp);
  tapmc::forbid_same_style_on_shared_atoms(lmp, this);
  tapmc::require_box_with_floor(lmp, "fix mc/settle");  // change_box may have made it another
  // the keyword sizes every atom the redeposition sees, the fixed obstacles outside the group too
  tapmc::check_radius_keyword_against_atoms(lmp, "fix mc/settle",
                                            fmt::format("diameter {}", 2.0 * fixed_radius),
                                            fixed_radius, group->bitmask[0], group->names[0], true);
  resolve_side_walls();
  check_dmax_against_periods();
  if (!atom->tag_enable)  // the schemes name and order the spheres by their IDs
    error->all(FLERR, "fix mc/settle: the atoms have no IDs ('atom_modify id no'); the "
               "redeposition orders and names the spheres by their IDs: use 'atom_modify id yes' "
               "(the default)");
  if (domain->boundary[2][0] == tapmc::kBoundaryFixed && z_floor < domain->boxlo[2])
    error->all(FLERR, "fix mc/settle: floor z0 = {} is below the fixed ('f') lower z face of the "
               "box, {}: spheres falling to the floor would leave the box and be lost; put the "
               "floor at or above the face, or make the lower z boundary shrink-wrapped",
               z_floor, domain->boxlo[2]);
  if (!container_region_id.empty()) {  // the region may have been redefined, the radii set
    const double r_max = count_movable() > 0 ? group_radius_extreme(true) : 0.0;
    container = tapmc::resolve_container(lmp, "fix mc/settle", container_region_id, r_max);
  }
  // every TAPMC style of the run in the same container, or all in the box
  tapmc::require_one_container(lmp, "fix", id, style, *this);
  find_tappers();
  bool all_move = count_movable() == atom->natoms;
  int tapped_bits = 0;
  for (const tapmc::Tapper *tapper : tappers) {
    const int tapper_group = dynamic_cast<const Fix *>(tapper)->igroup;
    all_move = all_move && tapper_group == 0;  // group 'all'
    tapped_bits |= group->bitmask[tapper_group];
  }
  other_movers = other_fixes_moving_atoms();
  check_after_taps = !all_move;
  if (!other_movers.empty() && comm->me == 0)
    error->warning(FLERR, "fix mc/settle: fix {} move(s) atoms besides the taps and the "
                   "redeposition: the spheres are checked for overlaps before each tap (hard "
                   "spheres are moved by fix tapdilate and fix mc/settle only; the floor, "
                   "xwalls/ywalls or a container hold the bed)", other_movers);
  // one pass: atoms no tap lifts, and atoms a tap lifts that no fix mc/settle redeposits
  const int settled_bits = settled_group_bits();
  long counts[2] = {0, 0}, counts_all[2] = {0, 0};
  for (int i = 0; i < atom->nlocal; ++i) {
    const bool tapped = atom->mask[i] & tapped_bits;
    counts[0] += !tapped;
    counts[1] += tapped && !(atom->mask[i] & settled_bits);
  }
  MPI_Allreduce(counts, counts_all, 2, MPI_LONG, MPI_SUM, world);
  // tapdilate dilates every atom of its group alike: tapped by any one fix, none stands still
  every_atom_tapped = counts_all[0] == 0;
  warn_tapped_never_redeposited(counts_all[1]);

  if (comm->me == 0 && update->whichflag == 2)
    error->warning(FLERR, "fix mc/settle moves atoms during minimization; use 'run' instead");

  tapmc::request_ghost_depth(lmp, redeposition->ghost_depth(group_radius_extreme(true)));
}

// Ghosts as deep as the scheme needs: a contact, its move margin and the ghost skin.
double FixMCSettle::DecomposedRedeposition::ghost_depth(double r_max)
{
  if (comm->style != 0)
    error->all(FLERR, "fix mc/settle: scheme domain needs the brick communication of LAMMPS "
               "('comm_style brick', the default); with 'comm_style tiled' use 'scheme gather'");
  tapmc::require_ghosts_of_every_atom(lmp, "fix mc/settle",
                                      "scheme domain would move spheres of neighbouring "
                                      "sub-domains into each other", ", or 'scheme gather'");
  const double depth = tapmc::DomainSettle::ghost_cutoff(r_max, fix.effective_d_max());
  kernel().set_verify(fix.verify_ghosts);
  return depth;
}

// Largest radius of all spheres (every sphere takes part in contacts), or smallest radius of the
// group's (d_max follows it), over all ranks (0 / +inf for none).
double FixMCSettle::group_radius_extreme(bool largest) const
{
  double value = largest ? 0.0 : std::numeric_limits<double>::infinity();
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!largest && !(atom->mask[i] & groupbit)) continue;
    const double r = fixed_radius > 0.0 ? fixed_radius : atom->radius[i];
    value = largest ? std::max(value, r) : std::min(value, r);
  }
  double all = value;
  MPI_Allreduce(&value, &all, 1, MPI_DOUBLE, largest ? MPI_MAX : MPI_MIN, world);
  return all;
}

long FixMCSettle::count_movable() const
{
  long local = 0, all = 0;
  for (int i = 0; i < atom->nlocal; ++i) local += (atom->mask[i] & groupbit) ? 1 : 0;
  MPI_Allreduce(&local, &all, 1, MPI_LONG, MPI_SUM, world);
  return all;
}

tapmc::DomainSettleSetup FixMCSettle::domain_setup() const
{
  tapmc::DomainSettleSetup setup;
  setup.groupbit = groupbit;
  setup.fixed_radius = fixed_radius;
  setup.planes = make_box();
  return setup;
}

// Every rank ends with all spheres, sorted by tag: xyz, radius, movable (= in the group).
void FixMCSettle::GatheredRedeposition::gather_system()
{
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const double *rad = atom->radius;

  // Owned atoms into the box with consistent image flags before their positions are shared.
  for (int i = 0; i < nlocal; ++i) domain->remap(x[i], atom->image[i]);

  pack_local.resize(static_cast<size_t>(kPackedPerAtom) * nlocal);
  for (int i = 0; i < nlocal; ++i) {
    double *p = &pack_local[static_cast<size_t>(kPackedPerAtom) * i];
    p[0] = static_cast<double>(tag[i]);
    p[1] = x[i][0];
    p[2] = x[i][1];
    p[3] = x[i][2];
    p[4] = fix.fixed_radius > 0.0 ? fix.fixed_radius : rad[i];
    p[5] = (mask[i] & fix.groupbit) ? 1.0 : 0.0;
  }
  const int nprocs = comm->nprocs;
  counts.resize(nprocs);
  displs.resize(nprocs);
  const int nsend = kPackedPerAtom * nlocal;
  MPI_Allgather(&nsend, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  long total = 0;
  for (int p = 0; p < nprocs; ++p) {
    displs[p] = static_cast<int>(total);
    total += counts[p];
  }
  pack_all.resize(total);
  MPI_Allgatherv(pack_local.data(), nsend, MPI_DOUBLE, pack_all.data(), counts.data(),
                 displs.data(), MPI_DOUBLE, world);

  const int n = static_cast<int>(total / kPackedPerAtom);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return pack_all[static_cast<size_t>(kPackedPerAtom) * a] <
           pack_all[static_cast<size_t>(kPackedPerAtom) * b];
  });
  gathered_to_sorted.resize(n);
  xyz.resize(3 * static_cast<size_t>(n));
  radius.resize(n);
  movable.resize(n);
  sorted_tag.resize(n);
  n_movable = 0;
  for (int s = 0; s < n; ++s) {
    const double *p = &pack_all[static_cast<size_t>(kPackedPerAtom) * order[s]];
    gathered_to_sorted[order[s]] = s;
    sorted_tag[s] = static_cast<tagint>(p[0]);
    xyz[3 * s] = p[1];
    xyz[3 * s + 1] = p[2];
    xyz[3 * s + 2] = p[3];
    radius[s] = p[4];
    movable[s] = p[5] != 0.0;
    n_movable += movable[s];
  }
}

// Owned atoms take their settled positions; image flags follow the periodic wraps the kernel
// counted, so unwrapped coordinates stay exact however far a sphere travels.
void FixMCSettle::GatheredRedeposition::scatter_positions()
{
  const int first = displs[comm->me] / kPackedPerAtom;
  double **x = atom->x;
  imageint *image = atom->image;
  for (int i = 0; i < atom->nlocal; ++i) {
    const size_t s = static_cast<size_t>(gathered_to_sorted[first + i]);
    x[i][0] = xyz[3 * s];
    x[i][1] = xyz[3 * s + 1];
    x[i][2] = xyz[3 * s + 2];
    const int shift_x = image_shift[2 * s], shift_y = image_shift[2 * s + 1];
    if (shift_x == 0 && shift_y == 0) continue;
    const imageint xbox = (image[i] & IMGMASK) - IMGMAX + shift_x;
    const imageint ybox = ((image[i] >> IMGBITS) & IMGMASK) - IMGMAX + shift_y;
    const imageint zbox = (image[i] >> IMG2BITS) - IMGMAX;
    image[i] = ((zbox + IMGMAX) & IMGMASK) << IMG2BITS | ((ybox + IMGMAX) & IMGMASK) << IMGBITS |
               ((xbox + IMGMAX) & IMGMASK);
  }
}

// The step bound of the trials: 'dmax', else kMaxStepOverRadius times the smallest radius of the
// group (collective).
double FixMCSettle::effective_d_max() const
{
  if (dmax_given) return d_max;
  return tapmc::defaults::kMaxStepOverRadius * group_radius_extreme(false);
}

void FixMCSettle::GatheredRedeposition::check_start(bool after_tap)
{
  gather_system();
  if (n_movable == 0)
    error->all(FLERR, "fix mc/settle: group '{}' has no atoms", group->names[fix.igroup]);
  for (size_t s = 0; s < radius.size(); ++s)
    if (!(radius[s] > 0.0))
      error->all(FLERR, "fix mc/settle: atom {} has radius {}; every sphere needs a radius > 0 "
                 "(set it with atom_style sphere / set diameter, or the 'diameter' keyword)",
                 sorted_tag[s], radius[s]);
  const tapmc::SettleBox box = fix.make_box();
  tapmc::Violation v;
  tapmc::guarded(lmp, "fix mc/settle", true, [&] {
    v = tapmc::Settler::find_violation(xyz.data(), radius.data(), static_cast<int>(radius.size()),
                                       box, tapmc::defaults::kContactTolerance);
  });
  if (v.i < 0) return;
  error->all(FLERR, fix.violation_message(v, sorted_tag[v.i], v.j >= 0 ? sorted_tag[v.j] : 0,
                                          after_tap));
}

void FixMCSettle::setup_pre_exchange()
{
  tapmc::require_exact_coordinates(
      lmp, "fix mc/settle", fixed_radius > 0.0 ? fixed_radius : tapmc::smallest_radius(lmp));
  redeposition->check_start(false);
  schedule_next_settle(update->ntimestep);
}

// Every step, before LAMMPS decides whether to reneighbour (and so whether pre_exchange runs):
// the redeposition steps again from the step before, as fix tapdilate does. A run with 'pre no'
// calls no setup hook, and after reset_timestep the last run's schedule never (or late) met the
// new steps: the run went on without a tap. The tapping fixes are read to schedule, so they are
// first checked to be the setup's.
void FixMCSettle::post_integrate()
{
  require_same_tappers();
  schedule_next_settle(update->ntimestep - 1);
}

// Each rank checks its spheres against its ghosts.
void FixMCSettle::DecomposedRedeposition::check_start(bool after_tap)
{
  if (fix.count_movable() == 0)
    error->all(FLERR, "fix mc/settle: group '{}' has no atoms", group->names[fix.igroup]);
  fix.require_positive_radii();
  kernel().distribute();
  if (!after_tap) kernel().check_round_widths(fix.domain_setup(), fix.effective_d_max());
  tapmc::Violation v;
  tapmc::guarded(lmp, "fix mc/settle", false,
                 [&] { v = kernel().find_violation(fix.domain_setup()); });
  // The lowest rank that found a violation states it; every rank stops with its message.
  const int mine = v.i >= 0 ? comm->me : comm->nprocs;
  int reporter = comm->nprocs;
  MPI_Allreduce(&mine, &reporter, 1, MPI_INT, MPI_MIN, world);
  if (reporter == comm->nprocs) return;
  std::string message;
  if (comm->me == reporter)
    message = fix.violation_message(v, atom->tag[v.i], v.j >= 0 ? atom->tag[v.j] : 0,
                                    after_tap);
  tapmc::broadcast_text(lmp, reporter, message);
  error->all(FLERR, message);
}

void FixMCSettle::pre_exchange()
{
  if (update->ntimestep != next_reneighbor) return;
  require_same_tappers();
  if (!other_movers.empty()) {  // before the taps: an overlap now is the other fixes' doing
    checking_other_movers = true;
    redeposition->check_start(true);
    checking_other_movers = false;
  }
  // The taps of this step come first, also those of tapping fixes defined after this fix
  // (LAMMPS calls pre_exchange in definition order); each taps once per step, and this step is
  // a tap step of at least one of them (schedule_next_settle).
  for (tapmc::Tapper *tap : tappers) tap->tap_if_due();
  schedule_next_settle(update->ntimestep);
  if (check_after_taps && !tappers.empty()) redeposition->check_start(true);

  const tapmc::SettleResult result = redeposition->settle();
  store_diagnostics(result);
  if (result.hit_cap && comm->me == 0)
    error->warning(FLERR, "fix mc/settle: step {}: redeposition stopped at the cap of {} sweeps "
                   "before <Z> converged to eta = {}", update->ntimestep, max_sweeps, eta);
  // Conditions that would repeat every tap: one warning per fix, from rank 0.
  auto warn_once = [&](bool &warned, const char *format, auto &&...args) {
    if (warned) return;
    warned = true;
    if (comm->me == 0) error->warning(FLERR, format, std::forward<decltype(args)>(args)...);
  };
  if (result.stopped_on_idle_check)
    warn_once(warned_idle_stop, "fix mc/settle: step {}: the redeposition stopped at a <Z> check "
              "in which none of its {} trials was accepted. 'stop change' reads an unchanged <Z> "
              "as converged; when one accepted move changes <Z> by more than eta (here {} "
              "movable spheres), that is its only way to stop, so the stop depends on the check "
              "interval, not on eta, and a small bed loosens tap after tap. 'stop drift' stops "
              "by eta at every N (warned once)", update->ntimestep,
              tapmc::Settler::trials_per_check(check_interval, result.movable), result.movable);
  taps_without_a_move = result.accepted == 0 && result.movable > 0 ? taps_without_a_move + 1 : 0;
  if (taps_without_a_move == tapmc::defaults::kSettleNoMoveTaps)
    warn_once(warned_no_move, "fix mc/settle: step {}: {} redepositions in a row accepted none "
              "of their trial moves ({} in the latest): the packing keeps each tap's dilation "
              "(<Z> = {:.6g} after the latest tap). Either the taps open gaps far narrower than "
              "the trial steps (up to dmax = {:.6g}; a tap of eps separates touching neighbours by "
              "at most eps times their diameter): use a larger eps or a smaller dmax; or "
              "the spheres are held sideways on every side (a column one diameter wide, spheres "
              "jammed between walls): every trial move has a sideways part (warned once)",
              update->ntimestep, taps_without_a_move, result.trials, result.mean_height,
              effective_d_max());
}

tapmc::SettleResult FixMCSettle::GatheredRedeposition::settle()
{
  gather_system();
  const tapmc::SettleParams params = fix.make_params(fix.effective_d_max(), n_movable);
  tapmc::SettleResult result;
  image_shift.assign(2 * radius.size(), 0);
  tapmc::guarded(lmp, "fix mc/settle", true, [&] {
    result = settler->settle(xyz.data(), radius.data(), movable.data(),
                             static_cast<int>(radius.size()), fix.make_box(), params,
                             image_shift.data());
  });
  scatter_positions();
  tapmc::relocate_moved_atoms(lmp, "fix mc/settle");
  return result;
}

tapmc::SettleResult FixMCSettle::DecomposedRedeposition::settle()
{
  const long n_movable = fix.count_movable();
  const tapmc::SettleParams params = fix.make_params(fix.effective_d_max(), n_movable);
  return kernel().settle(fix.domain_setup(), params, n_movable);
}

std::array<double, 6> FixMCSettle::DecomposedRedeposition::parallel_diagnostics() const
{
  const tapmc::DomainSettle::Timing &t = kernel().timing();
  return {static_cast<double>(kernel().ghost_rebuilds()), static_cast<double>(kernel().rounds()),
          t.trials, t.publish, t.reductions, t.rebuilds};
}

void FixMCSettle::store_diagnostics(const tapmc::SettleResult &result)
{
  last_trials = static_cast<double>(result.trials);
  last_sweeps = result.movable > 0 ? last_trials / static_cast<double>(result.movable) : 0.0;
  last_acceptance = result.trials > 0 ? double(result.accepted) / double(result.trials) : 0.0;
  last_mean_z = result.mean_height;
  last_mean_z0 = result.mean_height_start;
  last_hit_cap = result.hit_cap ? 1.0 : 0.0;
  last_idle_stop = result.stopped_on_idle_check ? 1.0 : 0.0;
  last_parallel = redeposition->parallel_diagnostics();
  // [9]-[12] as rank 0 timed them, on every rank: each rank's own seconds differ, and a variable,
  // 'if' or fix halt reading them would take other branches on other ranks (a hang)
  if (comm->nprocs > 1) MPI_Bcast(last_parallel.data(), 6, MPI_DOUBLE, 0, world);
}

// [1] sweeps used, [2] acceptance ratio, [3] <Z> after, [4] 1 if the sweep cap was hit,
// [5] trial moves, [6] <Z> before the redeposition (after the tap); scheme domain (else 0):
// [7] ghost rebuilds, [8] rounds, and rank 0's seconds in [9] trial moves, [10] ghost
// refreshes, [11] reductions, [12] migration and ghost rebuilds; [13] 1 if 'stop change' ended
// the redeposition at a check that accepted no trial (SettleResult::stopped_on_idle_check).
double FixMCSettle::compute_vector(int n)
{
  const double values[kVectorSize] = {
      last_sweeps,       last_acceptance,   last_mean_z,       last_hit_cap,
      last_trials,       last_mean_z0,      last_parallel[0],  last_parallel[1],
      last_parallel[2],  last_parallel[3],  last_parallel[4],  last_parallel[5],
      last_idle_stop};
  // thermo and variables check the index; the library interface (extract_fix) does not
  return n >= 0 && n < kVectorSize ? values[n] : std::numeric_limits<double>::quiet_NaN();
}
