// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute contacts: LAMMPS front end of the contact counter (tapmc_contacts.h). Each rank counts
// the contacts of its owned atoms of the group against its owned and ghost atoms of the group
// (the ghosts are the periodic images and the neighbouring sub-domains' spheres, so no axis is
// periodic for the counter): every owned atom gets its full count, and the global sums run over
// owned atoms only, one MPI_Allreduce of a packed buffer (plus one MAX of the largest count).
#include "compute_contacts.h"

#include "lammps_citation.h"
#include "lammps_compat.h"
#include "lammps_container.h"
#include "lammps_keywords.h"
#include "lammps_support.h"
#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "neighbor.h"
#include "update.h"

#include "tapmc_checks.h"
#include "tapmc_defaults.h"

#include <algorithm>
#include <limits>
#include <mpi.h>
#include <string>

using namespace LAMMPS_NS;
namespace contacts = tapmc::contacts;

namespace {
// Output vector layout (documented in doc/compute_contacts.rst).
// (The wall fraction came last, so that the entries before it kept their indices.)
enum VectorEntry {
  kMean,
  kFractionNone,
  kFractionFew,
  kFractionFloor,
  kLargest,
  kFractionWall,
  kVectorSize
};
constexpr int kArrayColumns = 2;  // Z, P(Z)
constexpr const char *kStyle = "compute contacts";
constexpr const char *kUsage =
    "compute ID group-ID contacts g [floor z0] [radius R] [container region-ID]";

const std::string kGapRange = "[0, " + tapmc::number(tapmc::defaults::kContactsMaxGap) + "]";
}  // namespace

ComputeContacts::ComputeContacts(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), fixed_radius_(0.0), nmax_(0)
{
  tapmc::cite_paper(lmp);
  if (domain->triclinic)
    error->all(FLERR, "{}: triclinic boxes are not supported; use an orthogonal box", kStyle);
  parse_arguments(narg, arg);
  if (!fixed_radius_ && !atom->radius_flag)
    error->all(FLERR, "{}: radius keyword required: atom style {} has no per-atom radius",
               kStyle, atom->atom_style);

  peratom_flag = 1;
  size_peratom_cols = 0;
  vector_flag = 1;
  size_vector = kVectorSize;
  extvector = 0;
  array_flag = 1;
  size_array_rows = contacts::kHistogramRows;
  size_array_cols = kArrayColumns;
  extarray = 0;
  comm_forward = 1;  // the group bit, for a dynamic group's ghosts

  vector = new double[kVectorSize];
  for (int i = 0; i < kVectorSize; ++i) vector[i] = 0.0;
  memory->create(array, contacts::kHistogramRows, kArrayColumns, "contacts:array");
  for (int z = 0; z < contacts::kHistogramRows; ++z) {
    array[z][0] = z;
    array[z][1] = 0.0;
  }
}

int ComputeContacts::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  const int *mask = atom->mask;
  for (int k = 0; k < n; ++k) buf[k] = (mask[list[k]] & groupbit) ? 1.0 : 0.0;
  return n;
}

void ComputeContacts::unpack_forward_comm(int n, int first, double *buf)
{
  int *mask = atom->mask;
  for (int k = 0; k < n; ++k) {
    if (buf[k] != 0.0)
      mask[first + k] |= groupbit;
    else
      mask[first + k] &= ~groupbit;
  }
}

// compute ID group contacts g [floor z0] [radius R]
void ComputeContacts::parse_arguments(int narg, char **arg)
{
  if (narg < 4)
    error->all(FLERR, "{}: the gap g is missing (relative to the contact distance R_i + R_j, in "
               "{}): {}", kStyle, kGapRange, kUsage);
  settings_.gap = tapmc::parse_real(lmp, kStyle, "gap", arg[3], kGapRange);
  if (!(settings_.gap >= 0.0 && settings_.gap <= tapmc::defaults::kContactsMaxGap))
    error->all(FLERR, "{}: {} (relative to the contact distance R_i + R_j)", kStyle,
               tapmc::outside_range_message("gap", arg[3], kGapRange));

  using tapmc::Keyword;
  const Keyword table[] = {
      {"floor", 1,
       [&](char **v) {
         settings_.floor = true;
         settings_.floor_z = tapmc::parse_real(lmp, kStyle, "floor", v[0]);
       }},
      {"radius", 1,
       [&](char **v) {
         fixed_radius_ = tapmc::parse_real(lmp, kStyle, "radius", v[0], "(0, +inf)");
         if (!(fixed_radius_ > 0.0 && fixed_radius_ < std::numeric_limits<double>::infinity()))
           error->all(FLERR, "{}: {}", kStyle,
                      tapmc::outside_range_message("radius", v[0], "(0, +inf)"));
       }},
      {tapmc::kContainerKeyword, 1, [&](char **v) { container_id_ = v[0]; }},
  };
  tapmc::parse_keywords(lmp, kStyle, table, 4, narg, arg);
  if (settings_.floor && domain->zperiodic)
    error->all(FLERR, "{}: the floor keyword needs a non-periodic z boundary (the box is "
               "periodic along z); use e.g. 'boundary p p fm'", kStyle);
  // the radii may not be set yet: init() checks them against the container
  resolve_container(0.0);
  // the kernel's one validation of the settings (ranges named there)
  tapmc::guarded(lmp, kStyle, true, [&] { contacts::validate(settings_); });
}

// The container's wall into the settings, checked against the box and (max_sphere_radius > 0)
// the largest sphere of the group: at definition and in init(), since the region, the box and
// the radii may change in between. Collective.
void ComputeContacts::resolve_container(double max_sphere_radius)
{
  settings_.wall = !container_id_.empty();
  if (settings_.wall)
    settings_.cylinder =
        tapmc::resolve_container(lmp, kStyle, container_id_, max_sphere_radius);
}

ComputeContacts::~ComputeContacts()
{
  delete[] vector;
  memory->destroy(array);
  memory->destroy(vector_atom);
}

void ComputeContacts::init()
{
  counted_step_ = -1;  // atoms may have moved between runs (displace_atoms) on the same step
  if (domain->triclinic)
    error->all(FLERR, "{}: triclinic boxes are not supported; use an orthogonal box", kStyle);
  tapmc::quiet_sorting_without_pair_style(lmp);
  tapmc::check_radius_keyword_against_atoms(lmp, kStyle, fmt::format("radius {}", fixed_radius_),
                                            fixed_radius_, groupbit, group->names[igroup], false);
  // a dynamic group is filled after init (at setup) and may take any atom later: the ghosts
  // and the container are sized for every atom
  const double r_max = group_radius_max(group->dynamic[igroup] != 0);
  // A periodic length below a diameter holds no hard-sphere packing (a sphere overlaps its own
  // image), and the ghosts would be images of images: (4 R / L)^3 of them per atom (a radius
  // of 1e3 in a box of 10 ran out of memory building them)
  for (int d = 0; d < 3; ++d)
    if (domain->periodicity[d] && domain->prd[d] < 2.0 * r_max)
      error->all(FLERR, "{}: the periodic box length along {} = {} is below the largest sphere "
                 "diameter {}: a sphere would overlap its own image (no hard-sphere packing); "
                 "check the radii or the 'radius' keyword, or widen the box", kStyle, "xyz"[d],
                 domain->prd[d], 2.0 * r_max);
  resolve_container(r_max);
  tapmc::require_ghosts_of_every_atom(lmp, kStyle, "the contacts across sub-domain and "
                                      "periodic faces would be missed", "", groupbit);
  // Ghosts deep enough for every contact. With a pair style (a DEM run) atoms move between
  // reneighbourings, up to skin/2 before LAMMPS rebuilds the ghosts: the skin is added. Without
  // one, atoms move only in TAPMC's taps and redepositions, each followed by a rebuild, and the
  // skin (an absolute length, 0.3 in lj units, 1 mm in si) is not added: in a bed of spheres of
  // 1e-3 it made LAMMPS copy 3 million periodic images of 300 spheres.
  tapmc::request_ghost_depth(lmp, ghost_depth_needed(r_max) +
                                      (force->pair != nullptr ? neighbor->skin : 0.0));
}

// Largest radius of the group's atoms, or of all atoms (any_atom_may_join: a dynamic group);
// collective; stops when one has no positive radius.
double ComputeContacts::group_radius_max(bool any_atom_may_join)
{
  if (fixed_radius_ > 0.0) return fixed_radius_;
  const int *mask = atom->mask;
  const double *radius = atom->radius;
  const int bits = any_atom_may_join ? group->bitmask[0] : groupbit;  // group 0: all
  double local[2] = {0.0, -std::numeric_limits<double>::infinity()};  // max R, -min R
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & bits)) continue;
    local[0] = std::max(local[0], radius[i]);
    local[1] = std::max(local[1], -radius[i]);
  }
  double global[2];
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, world);
  if (!(-global[1] > 0.0) && global[1] != -std::numeric_limits<double>::infinity())
    error->all(FLERR, "{}: per-atom radius must be > 0 (an atom of group {} has radius {})",
               kStyle, any_atom_may_join ? "all" : group->names[igroup], -global[1]);
  return global[0];
}

// The centre distance of the farthest possible contact: two spheres of the largest radius.
double ComputeContacts::ghost_depth_needed(double r_max) const
{
  return 2.0 * r_max * contacts::reach_factor(settings_.gap);
}

// The ghost shell LAMMPS built at the last set-up must hold every partner of every owned atom.
void ComputeContacts::check_ghost_shell(double r_max)
{
  if (!update->first_update)
    error->all(FLERR, "{} {}: invoked before the first run: it counts the contacts across "
               "sub-domain and periodic boundaries with ghost atoms, which exist once a run has "
               "set the system up; give 'run 0' first", kStyle, id);
  const double need = ghost_depth_needed(r_max);
  const double have = std::min({comm->cutghost[0], comm->cutghost[1], comm->cutghost[2]});
  if (have < need)
    error->all(FLERR, "{} {}: the ghost atoms reach {} beyond each sub-domain, but a contact "
               "within gap {} of spheres of radius up to {} reaches {}: set 'comm_modify cutoff "
               "{}' (or larger) and run again", kStyle, id, have, settings_.gap, r_max, need,
               need);
}

// counts_, on_floor_ and on_wall_ for the owned atoms of the group (owned_). Collective.
void ComputeContacts::count()
{
  counted_step_ = update->ntimestep;
  const double r_max = group_radius_max();
  check_ghost_shell(r_max);
  // A dynamic group's membership changes on owned atoms only (fix GROUP of LAMMPS 29 Sep 2021
  // does not refresh the ghosts' masks until the next rebuild): send it to the ghosts.
  if (group->dynamic[igroup]) tapmc::compat::forward_comm_compute(comm, this);
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const int *mask = atom->mask;
  double **x = atom->x;
  owned_.clear();
  xyz_.clear();
  radius_.clear();
  auto take = [&](int i) {
    xyz_.insert(xyz_.end(), {x[i][0], x[i][1], x[i][2]});
    radius_.push_back(fixed_radius_ > 0.0 ? fixed_radius_ : atom->radius[i]);
  };
  for (int i = 0; i < nlocal; ++i)
    if (mask[i] & groupbit) {
      owned_.push_back(i);
      take(i);
    }
  for (int i = nlocal; i < nall; ++i)
    if (mask[i] & groupbit) take(i);

  contacts::Spheres spheres;
  spheres.xyz = xyz_.data();
  spheres.radius = radius_.data();
  spheres.count = static_cast<int>(radius_.size());
  const int centres = static_cast<int>(owned_.size());
  counts_.assign(centres, 0);
  on_floor_.assign(centres, 0);
  on_wall_.assign(centres, 0);
  const contacts::Box no_periodic_axis;  // the ghosts are the images
  tapmc::guarded(lmp, kStyle, false, [&] {
    counter_.count(spheres, centres, no_periodic_axis, settings_, counts_.data(),
                   on_floor_.data(), on_wall_.data());
  });
}

// The counts of this step are at hand when one of the outputs was computed on it and no move
// since made its stamp stale (forget_computed_values sets every stamp of the step to
// kStampBeforeTheMove).
bool ComputeContacts::counts_current() const
{
  const bigint step = update->ntimestep;
  return counted_step_ == step &&
         (invoked_peratom == step || invoked_vector == step || invoked_array == step);
}

void ComputeContacts::compute_peratom()
{
  const bool current = counts_current();
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax_) {
    memory->destroy(vector_atom);
    nmax_ = atom->nmax;
    memory->create(vector_atom, nmax_, "contacts:vector_atom");
  }
  if (!current) count();
  for (int i = 0; i < atom->nlocal; ++i) vector_atom[i] = 0.0;
  for (std::size_t k = 0; k < owned_.size(); ++k) vector_atom[owned_[k]] = counts_[k];
}

// The vector and the distribution from the owned atoms' counts: one sum and one max reduction.
void ComputeContacts::summarize()
{
  double sums[contacts::kNumSums] = {};
  const int local_max = contacts::accumulate(counts_.data(), on_floor_.data(), on_wall_.data(),
                                             nullptr, static_cast<int>(counts_.size()), sums);
  MPI_Allreduce(MPI_IN_PLACE, sums, contacts::kNumSums, MPI_DOUBLE, MPI_SUM, world);
  int largest = 0;
  MPI_Allreduce(&local_max, &largest, 1, MPI_INT, MPI_MAX, world);
  const contacts::Distribution d = contacts::finish(sums, largest);
  vector[kMean] = d.mean;
  vector[kFractionNone] = d.fraction_none;
  vector[kFractionFew] = d.fraction_few;
  vector[kFractionFloor] = d.fraction_floor;
  vector[kLargest] = d.max;
  vector[kFractionWall] = d.fraction_wall;
  for (int z = 0; z < contacts::kHistogramRows; ++z) array[z][1] = d.fraction[z];
}

void ComputeContacts::compute_vector()
{
  const bool current = counts_current();
  invoked_vector = update->ntimestep;
  if (!current) count();
  summarize();
}

void ComputeContacts::compute_array()
{
  const bool current = counts_current();
  invoked_array = update->ntimestep;
  if (!current) count();
  summarize();
}

double ComputeContacts::memory_usage()
{
  return static_cast<double>(nmax_) * sizeof(double) +
         static_cast<double>(xyz_.capacity() + radius_.capacity()) * sizeof(double) +
         static_cast<double>(owned_.capacity() + counts_.capacity()) * sizeof(int) +
         static_cast<double>(on_floor_.capacity() + on_wall_.capacity());
}
