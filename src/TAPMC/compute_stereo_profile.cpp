// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute stereo/profile: LAMMPS front end of the exact stereology kernel (tapmc_stereology.h).
// Each rank sums over its owned atoms; one MPI_Allreduce of a packed buffer per output (plus one
// MAX reduction of the surface columns when the window top must be read from the data). With
// 'container' the same measures are taken in a vertical cylinder (tapmc_cylinder.h): the disk
// replaces the box's cross-section, the radial profile and the wall zone replace the vertical
// cuts and the lateral zones.
#include "compute_stereo_profile.h"

#include "lammps_box.h"
#include "lammps_citation.h"
#include "lammps_container.h"
#include "lammps_keywords.h"
#include "lammps_support.h"
#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "memory.h"
#include "update.h"
#include "utils.h"

#include "tapmc_defaults.h"
#include "tapmc_math.h"

#include <algorithm>
#include <limits>
#include <mpi.h>
#include <stdexcept>
#include <string>

using namespace LAMMPS_NS;
namespace stereo = tapmc::stereo;

namespace {
// Output vector layout (documented in doc/compute_stereo_profile.rst).
enum VectorEntry {
  kPhiBulk,
  kPhiCorrected,
  kMeanHeight,
  kWindowTop,
  kPhiLateral,
  kPhiCentral,
  kSurfaceHeight,
  kVectorSize
};
constexpr int kArrayColumns = 3;
// axis_ of the radial profile (axis r): coaxial cylindrical cuts of the container.
constexpr int kRadialAxis = 3;
}  // namespace

ComputeStereoProfile::ComputeStereoProfile(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), axis_(2), fixed_radius_(0.0), mean_radius_(0.0), group_count_(0.0), radius_ready_(false),
    floor_warned_(false), central_warned_(false), window_warned_(false)
{
  tapmc::cite_paper(lmp);
  tapmc::require_box_with_floor(lmp, "compute stereo/profile");

  settings_.floor = domain->boxlo[2];
  planes_.n = tapmc::defaults::kProfilePlanes;
  const bool planes_given = parse_keywords(narg, arg);

  if (!fixed_radius_ && !atom->radius_flag)
    error->all(FLERR,
               "compute stereo/profile: radius keyword required: atom style {} has no per-atom "
               "radius",
               atom->atom_style);
  if (has_container()) resolve_container();
  check_axis();

  // Vertical cuts are perpendicular to the profile axis, or to x when the profile is vertical
  // (the setting is unused in a container, whose zones are annuli).
  settings_.transverse_axis = axis_ == 0 || axis_ == 1 ? axis_ : 0;

  // Default plane range, fixed when the compute is defined (so that array rows keep their
  // positions for time averages): floor .. box zhi along z, the box along x or y, the axis to
  // the wall along r.
  if (!planes_given) {
    if (axis_ == kRadialAxis) {
      planes_.lo = 0.0;
      planes_.hi = cylinder_.radius;
    } else {
      planes_.lo = axis_ == 2 ? settings_.floor : domain->boxlo[axis_];
      planes_.hi = domain->boxhi[axis_];
    }
    if (!(planes_.lo < planes_.hi))
      error->all(FLERR,
                 "compute stereo/profile: default planes {} .. {} are empty (floor above the box "
                 "top); give planes lo hi n",
                 planes_.lo, planes_.hi);
  }
  // The kernel's one validation of every setting (ranges named there).
  tapmc::guarded(lmp, "compute stereo/profile", true, [&] {
    stereo::validate(settings_);
    stereo::validate(planes_);
  });
  if (axis_ == kRadialAxis && !(planes_.lo >= 0.0))
    error->all(FLERR, "compute stereo/profile: {} for axis r (radii from the container's axis)",
               tapmc::outside_range_message("planes lo", tapmc::number(planes_.lo),
                                            "[0, hi) = [0, " + tapmc::number(planes_.hi) + ")"));
  const int nplanes = planes_.n;

  vector_flag = 1;
  size_vector = kVectorSize;
  extvector = 0;
  array_flag = 1;
  size_array_rows = nplanes;
  size_array_cols = kArrayColumns;
  extarray = 0;

  vector = new double[kVectorSize];
  for (int i = 0; i < kVectorSize; ++i) vector[i] = 0.0;
  // the array is allocated when first computed (compute_array): a profile nobody reads, also
  // one of many planes, costs no memory
  array = nullptr;
}

// One table of keywords: name, number of values, what the values set. Returns whether
// 'planes' was given. Ranges are checked once, by the kernel (stereo::validate).
bool ComputeStereoProfile::parse_keywords(int narg, char **arg)
{
  using tapmc::Keyword;
  auto number = [&](const char *name, const char *text) {
    return tapmc::parse_real(lmp, "compute stereo/profile", name, text);
  };
  bool planes_given = false;
  const Keyword table[] = {
      {"floor", 1, [&](char **v) { settings_.floor = number("floor", v[0]); }},
      {"radius", 1,
       [&](char **v) {
         fixed_radius_ = number("radius", v[0]);
         if (!(fixed_radius_ > 0.0))
           error->all(FLERR, "compute stereo/profile: {}",
                      tapmc::outside_range_message("radius", v[0], "(0, +inf)"));
       }},
      {"axis", 1,
       [&](char **v) {
         const std::string axis = v[0];
         if (axis == "r") {
           axis_ = kRadialAxis;
           return;
         }
         if (axis != "x" && axis != "y" && axis != "z")
           error->all(FLERR,
                      "compute stereo/profile: axis = {} must be x, y or z (or r with a "
                      "container)",
                      axis);
         axis_ = axis[0] - 'x';
       }},
      {"planes", 3,
       [&](char **v) {
         planes_.lo = number("planes lo", v[0]);
         planes_.hi = number("planes hi", v[1]);
         planes_.n = static_cast<int>(tapmc::parse_integer(
             lmp, "compute stereo/profile", "planes n", v[2], 1, std::numeric_limits<int>::max()));
         planes_given = true;
       }},
      {"window", 2,
       [&](char **v) {
         settings_.window_lo = number("window lo", v[0]);
         settings_.window_hi = number("window hi", v[1]);
       }},
      {"lateral", 1, [&](char **v) { settings_.lateral_width = number("lateral", v[0]); }},
      {"top_fraction", 1, [&](char **v) { settings_.top_fraction = number("top_fraction", v[0]); }},
      {"bulk", 1, [&](char **v) { settings_.bulk_height = number("bulk", v[0]); }},
      {"column", 1, [&](char **v) { settings_.column_width = number("column", v[0]); }},
      {"wall_band", 1, [&](char **v) { settings_.wall_band = number("wall_band", v[0]); }},
      {"wall_factor", 1, [&](char **v) { settings_.wall_factor = number("wall_factor", v[0]); }},
      {tapmc::kContainerKeyword, 1, [&](char **v) { container_id_ = v[0]; }},
  };
  tapmc::parse_keywords(lmp, "compute stereo/profile", table, 3, narg, arg);
  return planes_given;
}

// The container's cylinder from its region, checked against the box and against the largest
// sphere of the group (or the radius keyword): at definition and in init(), since the region,
// the box and the radii may change in between. Collective.
void ComputeStereoProfile::resolve_container()
{
  double r_max = fixed_radius_;
  if (!(r_max > 0.0)) {
    double local = 0.0;
    for (int i = 0; i < atom->nlocal; ++i)
      if (atom->mask[i] & groupbit) local = std::max(local, atom->radius[i]);
    MPI_Allreduce(&local, &r_max, 1, MPI_DOUBLE, MPI_MAX, world);
  }
  cylinder_ = tapmc::resolve_container(lmp, "compute stereo/profile", container_id_, r_max);
}

// Which profiles exist where: vertical planes x = c or y = c in a box, coaxial surfaces (axis r)
// in a container; horizontal planes (axis z) in both.
void ComputeStereoProfile::check_axis()
{
  if (axis_ == kRadialAxis && !has_container())
    error->all(FLERR,
               "compute stereo/profile: axis = r (the radial profile) needs a cylindrical "
               "container: add 'container REGION-ID'");
  if (has_container() && (axis_ == 0 || axis_ == 1))
    error->all(FLERR,
               "compute stereo/profile: axis = {} is not available with container = {}; allowed: "
               "z (Phi(z) over the disk) or r (the radial profile)",
               "xy"[axis_], container_id_);
}

ComputeStereoProfile::~ComputeStereoProfile()
{
  delete[] vector;
  memory->destroy(array);
}

void ComputeStereoProfile::init()
{
  tapmc::require_box_with_floor(lmp, "compute stereo/profile");
  tapmc::check_radius_keyword_against_atoms(lmp, "compute stereo/profile",
                                            fmt::format("radius {}", fixed_radius_),
                                            fixed_radius_, groupbit, group->names[igroup], false);
  if (has_container()) resolve_container();
  // The packing fractions divide by the box's horizontal area: a shrink-wrapped side spans the
  // sphere centres, not the bed (a simple cubic lattice read 0.684 for pi/6 = 0.524).
  for (int dim = 0; dim < 2 && !has_container(); ++dim)
    if (!domain->periodicity[dim] && (domain->boundary[dim][0] != tapmc::kBoundaryFixed ||
                                      domain->boundary[dim][1] != tapmc::kBoundaryFixed))
      error->all(FLERR, "compute stereo/profile: the {0} boundary is shrink-wrapped, so the box "
                 "spans the sphere centres, not the bed, and the packing fractions would divide "
                 "by too small an area; use 'boundary f' in {0} with the walls at the box faces "
                 "(or a periodic {0}, or a container)", "xy"[dim]);
  tapmc::quiet_sorting_without_pair_style(lmp);
  tapmc::request_ghost_depth(lmp, 2.0 * tapmc::largest_radius(lmp));
  update_mean_radius();
  floor_warned_ = false;
  // warn about an empty central zone here, before the run's output starts (its width depends
  // on the box and R only); compute_vector checks again (box changes, library use before a run)
  if (group_count_ > 0.0) {
    const stereo::Box box = measure_box();
    warn_empty_central_zone(stereo::resolve_windows(settings_, box, mean_radius_, settings_.floor),
                            box);
  }
}

// An empty group (now): mean radius 0 after a fresh look at the group. Collective.
bool ComputeStereoProfile::group_is_empty()
{
  if (!radius_ready_ || group_count_ == 0.0) update_mean_radius();
  return group_count_ == 0.0;
}

// Heights, <Z> and the 16/11 wall band are measured from the floor: a sphere of the group
// reaching below it (beyond the contact tolerance) means the floor is not the one under the
// packing. One warning per run, naming the lowest sphere. Collective.
void ComputeStereoProfile::warn_below_floor()
{
  if (floor_warned_) return;
  const int *mask = atom->mask;
  double **x = atom->x;
  struct {
    double excess;  // (floor - bottom) / diameter: > tolerance means below the floor
    int rank;
  } local{-std::numeric_limits<double>::infinity(), comm->me}, global;
  double bottom = 0.0;
  tagint tag = 0;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    const double r = fixed_radius_ > 0.0 ? fixed_radius_ : atom->radius[i];
    const double excess = (settings_.floor - (x[i][2] - r)) / (2.0 * r);
    if (excess > local.excess) {
      local.excess = excess;
      bottom = x[i][2] - r;
      tag = atom->tag ? atom->tag[i] : 0;
    }
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (!(global.excess > tapmc::defaults::kContactTolerance)) return;
  MPI_Bcast(&bottom, 1, MPI_DOUBLE, global.rank, world);
  MPI_Bcast(&tag, 1, MPI_LMP_TAGINT, global.rank, world);
  floor_warned_ = true;
  if (comm->me == 0)
    error->warning(FLERR, "compute stereo/profile: atom {} of group {} reaches down to z = {}, "
                   "below the floor z0 = {}: heights, <Z> and the wall correction are measured "
                   "from the floor; set 'floor' at or below the bottom of the packing",
                   tag, group->names[igroup], bottom, settings_.floor);
}

// The lateral zones meet at the middle of the box: no central zone, so vector entry 6 is NaN
// (the kernel's finish_summary). One warning per compute (named by its ID), with the widths and
// what would give a central zone. The windows are the same on every rank (reduced data); rank 0
// writes. Called at init (so that the warning comes before the run's thermo output) and on
// every vector invocation.
void ComputeStereoProfile::warn_empty_central_zone(const stereo::Windows &w, const stereo::Box &box)
{
  if (has_container()) {
    warn_empty_core(w);
    return;
  }
  if (central_warned_ || w.central_width() > 0.0) return;
  central_warned_ = true;
  if (comm->me != 0) return;
  const int a = w.transverse_axis;
  const char axis = "xy"[a];
  const double length = box.length(a);
  error->warning(FLERR,
                 "compute stereo/profile {}: no central zone: the lateral zones (lateral = {:.6g} "
                 "from both {} faces) cover the whole box width {:.6g} along {}, so the central "
                 "mean (vector entry 6) is NaN; a central zone needs lateral < {:.6g} (half the "
                 "box width) or a box wider than {:.6g} (2 lateral) along {}",
                 id, w.lateral_width, axis, length, axis, 0.5 * length, 2.0 * w.lateral_width,
                 axis);
}

// The vertical window [lo, hi] (default floor + 2R to the window top) is empty in a bed of about
// one layer: what it bounds (`what`: the vector's zone means, or the array's profile of vertical
// or coaxial cuts) is NaN. Once per compute and output (`warned`); every rank has the same
// window (reduced data), rank 0 writes.
void ComputeStereoProfile::warn_empty_window(double lo, double hi, bool &warned,
                                             const std::string &what)
{
  if (warned || hi > lo) return;
  warned = true;
  if (comm->me != 0) return;
  error->warning(FLERR,
                 "compute stereo/profile {}: empty vertical window: its top z = {:.6g} is not "
                 "above its bottom z = {:.6g} (a bed of about one layer, below floor + 2R), so "
                 "{} are NaN; give 'window lo hi' to choose the heights", id, hi, lo, what);
}

// In a container the central zone is the core, inside the wall zone (lateral = w from the wall):
// none when w reaches the axis (finish_cylinder_zones gives NaN). Once per compute, as above.
void ComputeStereoProfile::warn_empty_core(const stereo::Windows &w)
{
  if (central_warned_ || cylinder_.radius - w.lateral_width > 0.0) return;
  central_warned_ = true;
  if (comm->me != 0) return;
  error->warning(FLERR,
                 "compute stereo/profile {}: no core: the wall zone (lateral = {:.6g} from the "
                 "wall of container {}) covers the whole container radius {:.6g}, so the core "
                 "mean (vector entry 6) is NaN; a core needs lateral < {:.6g} (the container "
                 "radius) or a container radius above {:.6g}",
                 id, w.lateral_width, container_id_, cylinder_.radius, cylinder_.radius,
                 w.lateral_width);
}

// The radius R behind every default (bulk 4R, lateral 7R, columns 2R, ...): the fixed radius, or
// the mean per-atom radius of the group, computed once per run (radii do not change in a run),
// or at the first invocation when the compute is used before any run (library interface).
void ComputeStereoProfile::update_mean_radius()
{
  radius_ready_ = true;
  const int *mask = atom->mask;
  const double *radius = atom->radius;
  double local[3] = {0.0, 0.0, 0.0};  // sum of radii, count, count with radius <= 0
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    const double r = fixed_radius_ > 0.0 ? fixed_radius_ : radius[i];
    local[0] += r;
    local[1] += 1.0;
    if (!(r > 0.0)) local[2] += 1.0;
  }
  double total[3];
  MPI_Allreduce(local, total, 3, MPI_DOUBLE, MPI_SUM, world);
  if (total[2] > 0.0)
    error->all(FLERR,
               "compute stereo/profile: per-atom radius must be > 0 ({} atoms of group {} have "
               "radius <= 0)",
               static_cast<long>(total[2]), group->names[igroup]);
  group_count_ = total[1];
  mean_radius_ = fixed_radius_ > 0.0 ? fixed_radius_ : (total[1] > 0.0 ? total[0] / total[1] : 0.0);
}

stereo::Spheres ComputeStereoProfile::select_spheres()
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  selected_.clear();
  for (int i = 0; i < nlocal; ++i)
    if (mask[i] & groupbit) selected_.push_back(i);
  stereo::Spheres s;
  s.xyz = (nlocal > 0 && atom->x) ? atom->x[0] : nullptr;
  if (fixed_radius_ > 0.0)
    s.uniform_radius = fixed_radius_;
  else
    s.radius = atom->radius;
  s.index = selected_.data();
  s.count = static_cast<int>(selected_.size());
  return s;
}

stereo::Box ComputeStereoProfile::current_box() const
{
  stereo::Box box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = domain->boxlo[d];
    box.hi[d] = domain->boxhi[d];
  }
  box.periodic[0] = domain->xperiodic != 0;
  box.periodic[1] = domain->yperiodic != 0;
  return box;
}

// The horizontal extent the measures use: the box, or the container's bounding square (its
// columns define h_s; its lateral zones are unused, the zones are annuli of the cylinder).
stereo::Box ComputeStereoProfile::measure_box() const
{
  if (!has_container()) return current_box();
  return stereo::bounding_box(cylinder_, domain->boxlo[2], domain->boxhi[2]);
}

// h_s: every rank marks the highest sphere top per column, one MAX reduction, then the mean.
double ComputeStereoProfile::reduce_surface_height(const stereo::Spheres &spheres,
                                                   const stereo::Box &box)
{
  const stereo::ColumnGrid grid =
      stereo::surface_column_grid(box, settings_, mean_radius_);
  buffer_.assign(grid.size(), -std::numeric_limits<double>::infinity());
  stereo::accumulate_column_tops(spheres, grid, buffer_.data());
  MPI_Allreduce(MPI_IN_PLACE, buffer_.data(), grid.size(), MPI_DOUBLE, MPI_MAX, world);
  return stereo::surface_height(buffer_.data(), grid.size(), settings_.floor);
}

// The group has spheres to measure (else the caller fills its empty output); warns once per run
// about a sphere below the floor. Collective.
bool ComputeStereoProfile::ready_to_measure()
{
  if (group_is_empty()) return false;
  warn_below_floor();
  return true;
}

void ComputeStereoProfile::compute_vector()
{
  invoked_vector = update->ntimestep;
  if (ready_to_measure()) {
    tapmc::guarded(lmp, "compute stereo/profile", false, [&] { compute_vector_guarded(); });
    return;
  }
  // no sphere: every fraction 0, z_top = h_s = z0 (see the doc page)
  for (int i = 0; i < kVectorSize; ++i) vector[i] = 0.0;
  vector[kWindowTop] = vector[kSurfaceHeight] = settings_.floor;
}

void ComputeStereoProfile::compute_vector_guarded()
{
  const stereo::Spheres spheres = select_spheres();
  const stereo::Box box = measure_box();
  const double surface = reduce_surface_height(spheres, box);
  const stereo::Windows windows = stereo::resolve_windows(settings_, box, mean_radius_, surface);

  double sums[stereo::kNumSummarySums] = {};
  if (has_container())
    stereo::accumulate_cylinder_summary(spheres, cylinder_, windows, sums);
  else
    stereo::accumulate_summary(spheres, box, windows, sums);
  MPI_Allreduce(MPI_IN_PLACE, sums, stereo::kNumSummarySums, MPI_DOUBLE, MPI_SUM, world);
  const stereo::Summary s = has_container()
                                ? stereo::finish_cylinder_summary(sums, cylinder_, windows)
                                : stereo::finish_summary(sums, box, windows);
  warn_empty_central_zone(windows, box);
  warn_empty_window(windows.window_lo, windows.window_hi, window_warned_,
                    "the lateral and central means (vector entries 5 and 6)");

  vector[kPhiBulk] = s.phi_bulk;
  vector[kPhiCorrected] = s.phi_corrected;
  vector[kMeanHeight] = s.mean_height;
  vector[kWindowTop] = s.top;
  vector[kPhiLateral] = s.phi_lateral;
  vector[kPhiCentral] = s.phi_central;
  vector[kSurfaceHeight] = s.surface;
}

void ComputeStereoProfile::compute_array()
{
  invoked_array = update->ntimestep;
  if (!array) {  // first use: LAMMPS's message on failure names the bytes and this text
    const std::string what = fmt::format("compute stereo/profile (planes n = {} rows of {})",
                                         planes_.n, kArrayColumns);
    memory->create(array, planes_.n, kArrayColumns, what.c_str());
  }
  if (ready_to_measure()) {
    tapmc::guarded(lmp, "compute stereo/profile", false, [&] { compute_array_guarded(); });
    return;
  }
  // no sphere: plane positions, zero fractions
  for (int k = 0; k < planes_.n; ++k) {
    array[k][0] = planes_.position(k);
    array[k][1] = array[k][2] = 0.0;
  }
}

void ComputeStereoProfile::compute_array_guarded()
{
  const stereo::Spheres spheres = select_spheres();
  const stereo::Box box = measure_box();

  // z-window of vertical (or coaxial) cuts: only the default top needs the data (h_s)
  double za = 0.0, zb = 0.0;
  if (axis_ != 2) {
    stereo::Windows windows;
    if (!settings_.window_hi) {
      const double surface = reduce_surface_height(spheres, box);
      windows = stereo::resolve_windows(settings_, box, mean_radius_, surface);
    }
    stereo::default_vertical_window(settings_, windows, mean_radius_, za, zb);
    warn_empty_window(za, zb, profile_window_warned_,
                      fmt::format("the {} profile's Phi and bin means (array columns 2 and 3)",
                                  axis_ == kRadialAxis ? 'r' : "xy"[axis_]));
  }

  const int n = planes_.n;
  buffer_.assign(2 * n, 0.0);  // cut areas, then bin volumes
  double *cut = buffer_.data(), *volume = buffer_.data() + n;
  if (axis_ == kRadialAxis)
    stereo::accumulate_radial_profile(spheres, cylinder_, planes_, za, zb, cut, volume);
  else if (has_container())
    stereo::accumulate_cylinder_profile(spheres, cylinder_, planes_, cut, volume);
  else
    stereo::accumulate_profile(spheres, box, axis_, planes_, za, zb, cut, volume);
  MPI_Allreduce(MPI_IN_PLACE, buffer_.data(), 2 * n, MPI_DOUBLE, MPI_SUM, world);
  if (axis_ == kRadialAxis)
    stereo::finish_radial_profile(cut, volume, planes_, za, zb, array[0]);
  else if (has_container())
    stereo::finish_cylinder_profile(cut, volume, cylinder_, planes_, array[0]);
  else
    stereo::finish_profile(cut, volume, box, axis_, planes_, za, zb, array[0]);
}

double ComputeStereoProfile::memory_usage()
{
  return (array ? static_cast<double>(planes_.n) * kArrayColumns * sizeof(double) : 0.0) +
         static_cast<double>(selected_.capacity()) * sizeof(int) +
         static_cast<double>(buffer_.capacity()) * sizeof(double);
}

// The box faces along a non-periodic x or y: the compute's area and lateral zones are the box's
// (none in a container, whose wall fix mc/settle compares as the container).
bool ComputeStereoProfile::side_walls(int dim, double &lo, double &hi) const
{
  if (dim < 0 || dim > 1 || domain->periodicity[dim] || !container_id_.empty()) return false;
  lo = domain->boxlo[dim];
  hi = domain->boxhi[dim];
  return true;
}
