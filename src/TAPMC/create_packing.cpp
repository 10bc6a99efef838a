// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// create_packing: runs the deposition kernel on rank 0 and gives every rank its own atoms.
#include "create_packing.h"

#include "lammps_box.h"
#include "lammps_citation.h"
#include "lammps_compat.h"
#include "lammps_container.h"
#include "lammps_support.h"
#include "tapmc_defaults.h"
#include "tapmc_deposition.h"
#include "tapmc_math.h"
#include "tapmc_stereology.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "irregular.h"
#include "region.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <limits>
#include <mpi.h>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// Where to deposit: the keywords floor, region and walls.
struct Options {
  double floor_z = 0.0;
  bool floor_given = false;
  std::string region_id;
  std::string container_id;  // 'container REGION-ID': a vertical cylinder (lammps_container.h)
  bool walls_given = false;
  bool walls_x = false, walls_y = false;
};

// Ownership of a point by this rank: half-open sub-domain intervals, the outermost sub-domains
// extended to infinity so that every point (also at a rounding distance outside the box, or
// above a shrink-wrapped top) has exactly one owner.
struct SubDomain {
  double lo[3], hi[3];
  bool open_lo[3], open_hi[3];
  bool owns(const double *x) const
  {
    for (int d = 0; d < 3; ++d) {
      if (!open_lo[d] && x[d] < lo[d]) return false;
      if (!open_hi[d] && x[d] >= hi[d]) return false;
    }
    return true;
  }
};

SubDomain my_subdomain(Domain *domain, Comm *comm)
{
  SubDomain s;
  for (int d = 0; d < 3; ++d) {
    s.lo[d] = domain->sublo[d];
    s.hi[d] = domain->subhi[d];
    if (comm->layout != Comm::LAYOUT_TILED) {
      s.open_lo[d] = comm->myloc[d] == 0;
      s.open_hi[d] = comm->myloc[d] == comm->procgrid[d] - 1;
    } else {
      s.open_lo[d] = comm->mysplit[d][0] == 0.0;
      s.open_hi[d] = comm->mysplit[d][1] == 1.0;
    }
  }
  return s;
}

// The command's arguments: N, R, dispersity, density (the kernel's parameters), type, seed and
// where to deposit.
struct Request {
  tapmc::PackingParams params;
  int type = 0;
  std::int64_t seed = 0;
  Options opt;
};

// Where the spheres go: the kernel's domain and what the messages and the report name.
struct Plan {
  tapmc::DepositionDomain dd;
  bool walls[2] = {false, false};
  bool top_fixed = false;
  std::string top_name;  // "" for an open top
  std::string where;     // "the box", "region 'ID'" or "container 'ID'"
  bool has_cylinder = false;
  tapmc::Cylinder cylinder;
  double r_min = 0.0, r_max = 0.0;
  double r_smallest = 0.0;  // of the created and the existing spheres (the coordinate bound)
};

void check_preconditions(LAMMPS *lmp, int narg)
{
  const char *usage = "create_packing N type R seed [floor z0] [region ID] "
                      "[walls x y|x|y|none] [container ID] [dispersity W] [density rho]";
  Error *error = lmp->error;
  if (!lmp->domain->box_exist)
    error->all(FLERR, "create_packing: no simulation box yet; define one with create_box or "
               "read_data first");
  if (narg < 4)
    error->all(FLERR, "create_packing: expected '{}', got {} argument(s)", usage, narg);
  if (!lmp->atom->radius_flag || !lmp->atom->rmass_flag)
    error->all(FLERR, "create_packing: the atom style has no per-atom radius and mass; use "
               "atom_style sphere");
  tapmc::require_box_with_floor(lmp, "create_packing");  // 3d, orthogonal, a floor
}

// 'walls' takes one or two of x, y, or none: returns how many values it used.
int parse_walls(LAMMPS *lmp, Options &opt, int iarg, int narg, char **arg)
{
  opt.walls_given = true;
  opt.walls_x = opt.walls_y = false;  // the last 'walls' holds, as the last of any keyword
  int used = 0;
  for (int k = iarg + 1; k < narg && k <= iarg + 2; ++k) {
    const std::string v = arg[k];
    if (v == "x") opt.walls_x = true;
    else if (v == "y") opt.walls_y = true;
    else if (v == "none" && used == 0) { ++used; break; }
    else break;
    ++used;
  }
  if (used == 0) lmp->error->all(FLERR, "create_packing: walls needs 'x', 'y', 'x y' or 'none'");
  // 'walls none x' read 'x' as the next keyword ("keyword 'x' needs a value")
  const int next = iarg + 1 + used;
  if (std::string(arg[iarg + 1]) == "none" && next < narg &&
      (std::string(arg[next]) == "x" || std::string(arg[next]) == "y"))
    lmp->error->all(FLERR, "create_packing: walls none {}: 'none' stands alone; give 'walls x', "
                    "'walls y', 'walls x y' or 'walls none'", arg[next]);
  return used;
}

void parse_options(LAMMPS *lmp, int narg, char **arg, Request &req)
{
  Error *error = lmp->error;
  Options &opt = req.opt;
  for (int iarg = 4; iarg < narg;) {
    const std::string key = arg[iarg];
    if (key == "walls") {
      iarg += 1 + parse_walls(lmp, opt, iarg, narg, arg);
      continue;
    }
    if (iarg + 1 >= narg) error->all(FLERR, "create_packing: keyword '{}' needs a value", key);
    const char *value = arg[iarg + 1];
    if (key == "floor") {
      opt.floor_z = tapmc::parse_real(lmp, "create_packing", "floor", value);
      opt.floor_given = true;
    } else if (key == "region") {
      opt.region_id = value;
    } else if (key == tapmc::kContainerKeyword) {
      opt.container_id = value;
    } else if (key == "dispersity") {
      req.params.dispersity = tapmc::parse_real(lmp, "create_packing", "dispersity", value);
    } else if (key == "density") {
      req.params.density = tapmc::parse_real(lmp, "create_packing", "density", value);
    } else {
      error->all(FLERR, "create_packing: unknown keyword '{}' (allowed: floor, region, walls, "
                 "container, dispersity, density)", key);
    }
    iarg += 2;
  }
}

Request parse_request(LAMMPS *lmp, int narg, char **arg)
{
  check_preconditions(lmp, narg);
  Request req;
  req.params.n = tapmc::parse_long(lmp, "create_packing", "N", arg[0]);  // range: validate
  req.type = static_cast<int>(tapmc::parse_integer(lmp, "create_packing", "type", arg[1], 1,
                                                   std::max(1, lmp->atom->ntypes),
                                                   "the atom types of the box"));
  req.params.radius = tapmc::parse_real(lmp, "create_packing", "radius", arg[2]);
  req.seed = tapmc::parse_seed(lmp, "create_packing", "seed", arg[3]);
  parse_options(lmp, narg, arg, req);
  tapmc::guarded(lmp, "create_packing", true, [&] { tapmc::validate(req.params); });
  return req;
}

// The x-y extent (box, clipped to the region), side conditions, floor and top.
Plan plan_domain(LAMMPS *lmp, const Request &req)
{
  Domain *domain = lmp->domain;
  Error *error = lmp->error;
  const Options &opt = req.opt;
  Plan plan;
  double lo[3] = {domain->boxlo[0], domain->boxlo[1], domain->boxlo[2]};
  double hi[3] = {domain->boxhi[0], domain->boxhi[1], domain->boxhi[2]};
  plan.top_fixed = domain->boundary[2][1] == tapmc::kBoundaryFixed;
  double z_top = plan.top_fixed ? domain->boxhi[2] : std::numeric_limits<double>::infinity();
  plan.top_name = plan.top_fixed ? "the fixed box top" : "";
  bool spans[2] = {true, true};
  if (!opt.region_id.empty()) {
    Region *region = tapmc::compat::find_region(domain, opt.region_id);
    if (!region) error->all(FLERR, "create_packing: region ID '{}' does not exist", opt.region_id);
    if (!region->bboxflag)
      error->all(FLERR, "create_packing: region '{}' has no bounding box (use a block)",
                 opt.region_id);
    const double rlo[3] = {region->extent_xlo, region->extent_ylo, region->extent_zlo};
    const double rhi[3] = {region->extent_xhi, region->extent_yhi, region->extent_zhi};
    for (int d = 0; d < 3; ++d) {
      if (d < 2) spans[d] = rlo[d] <= domain->boxlo[d] && rhi[d] >= domain->boxhi[d];
      lo[d] = std::max(lo[d], rlo[d]);
      hi[d] = std::min(hi[d], rhi[d]);
      if (d < 2 && !(hi[d] > lo[d]))
        error->all(FLERR, "create_packing: region '{}' lies outside the box in {} (region {} to "
                   "{}, box {} to {}): the spheres are deposited in the part of the region "
                   "inside the box", opt.region_id, "xy"[d], rlo[d], rhi[d], domain->boxlo[d],
                   domain->boxhi[d]);
    }
    if (rhi[2] < z_top) {
      z_top = rhi[2];
      plan.top_name = "the top of region '" + opt.region_id + "'";
    }
  }
  const bool periodic_box[2] = {domain->xperiodic != 0, domain->yperiodic != 0};
  if (!opt.container_id.empty()) {
    // the tube replaces the side conditions: its wall is the only side support
    if (opt.walls_given || !opt.region_id.empty())
      error->all(FLERR, "create_packing: container {} and {} both given; a container is the "
                 "whole deposition domain in x and y: give one of them", opt.container_id,
                 opt.walls_given ? "walls" : "region " + opt.region_id);
    plan.has_cylinder = true;
    plan.cylinder = tapmc::resolve_container(lmp, "create_packing", opt.container_id,
                                             req.params.radii().r_max);
  }
  for (int d = 0; d < 2 && !plan.has_cylinder; ++d) {
    const bool can_wrap = periodic_box[d] && spans[d];
    const bool asked = d == 0 ? opt.walls_x : opt.walls_y;
    plan.walls[d] = opt.walls_given ? asked : !can_wrap;
    if (!plan.walls[d] && !can_wrap)
      error->all(FLERR, "create_packing: walls: the {} direction needs walls (the box is not "
                 "periodic in {}, or the region is narrower than the box)", "xy"[d], "xy"[d]);
    // Walls at the box faces need fixed faces: LAMMPS widens a shrink-wrapped box by 1e-4 of its
    // length (the packing then reached past walls set at the region's faces) and moves it.
    if (plan.walls[d] && opt.region_id.empty() && !periodic_box[d] &&
        (domain->boundary[d][0] != tapmc::kBoundaryFixed ||
         domain->boundary[d][1] != tapmc::kBoundaryFixed))
      error->all(FLERR, "create_packing: the {0} boundary is shrink-wrapped, so the box faces are "
                 "no walls (LAMMPS widens the box by 1e-4 of its length and moves it with the "
                 "atoms); use 'boundary f' in {0}, or 'region ID' with the walls at its faces",
                 "xy"[d]);
  }
  const double z_floor = opt.floor_given ? opt.floor_z : lo[2];
  if (z_floor < domain->boxlo[2])
    error->all(FLERR, "create_packing: floor = {} is below the box bottom {}", z_floor,
               domain->boxlo[2]);
  if (!(z_top > z_floor))
    error->all(FLERR, "create_packing: floor = {} is not below {} (z = {})", z_floor,
               plan.top_name, z_top);

  plan.r_min = req.params.radii().r_min;
  plan.r_max = req.params.radii().r_max;
  plan.r_smallest = std::min(plan.r_min, tapmc::smallest_radius(lmp));
  tapmc::require_exact_coordinates(lmp, "create_packing", plan.r_smallest);
  // An open top grows with the packing: the floor may lie above the box, and the packing
  // above that (checked once deposited)
  tapmc::require_exact_coordinate(lmp, "create_packing", "the floor z", 'z', z_floor,
                                  plan.r_smallest);
  tapmc::DepositionDomain &dd = plan.dd;
  dd.xlo = lo[0];
  dd.xhi = hi[0];
  dd.ylo = lo[1];
  dd.yhi = hi[1];
  dd.periodic_x = !plan.walls[0];
  dd.periodic_y = !plan.walls[1];
  dd.z_floor = z_floor;
  dd.z_top = z_top;
  plan.where = opt.region_id.empty() ? std::string("the box") : "region '" + opt.region_id + "'";
  if (plan.has_cylinder) {
    dd.periodic_x = dd.periodic_y = false;
    dd.has_cylinder = true;
    dd.cylinder = plan.cylinder;
    plan.where = "container '" + opt.container_id + "'";
  }
  return plan;
}

// Refuses a domain narrower than one sphere, or (cheaply, before depositing) one that could not
// hold the spheres even at random close packing.
void check_room(LAMMPS *lmp, const Request &req, const Plan &plan)
{
  const tapmc::DepositionDomain &dd = plan.dd;
  const double width[2] = {dd.xhi - dd.xlo, dd.yhi - dd.ylo};
  for (int d = 0; d < 2; ++d)
    if (width[d] < 2.0 * plan.r_max)
      lmp->error->all(FLERR, "create_packing: {} is {} wide in {}, less than one sphere diameter "
                      "{}; it cannot hold the spheres", plan.where, width[d], "xy"[d],
                      2.0 * plan.r_max);
  if (!std::isfinite(dd.z_top)) return;
  const double radius = req.params.radius, w = req.params.dispersity;
  const double mean_r3 = radius * radius * radius * (1.0 + w * w);
  const double packing = tapmc::defaults::kRandomClosePacking;
  const double need = req.params.n * (4.0 / 3.0) * tapmc::kPi * mean_r3 / packing;
  const double area = plan.has_cylinder ? tapmc::kPi * plan.cylinder.radius * plan.cylinder.radius
                                        : width[0] * width[1];
  const double room = area * (dd.z_top - dd.z_floor);
  if (need > room)
    lmp->error->all(FLERR, "create_packing: {} cannot hold N = {} spheres of radius {}: they need "
                    "at least {:.6g} of volume (at packing fraction {}), {} offers {:.6g} between "
                    "the floor z = {} and {} z = {}", plan.where, req.params.n, radius, need,
                    packing, plan.where, room, dd.z_floor, plan.top_name, dd.z_top);
}

// Memory per sphere: rank 0 adds the deposition (kernel, packing, allocator slack) to the LAMMPS
// atoms that every rank holds for its own. Measured as the growth of each rank's peak resident
// size from N = 1e5 to 3e5 (atom_style sphere, LAMMPS 29 Sep 2021, x86-64): 299 bytes per sphere
// on 1 rank, 165 + 73 on 2 ranks; the sum below bounds both.
constexpr double kDepositionBytesPerSphere = 160.0;
constexpr double kAtomBytesPerSphere = 145.0;
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// What the deposition and the atoms of the ranks beside rank 0 need where rank 0 runs, in bytes
// (collective).
double memory_needed_by_rank0_node(LAMMPS *lmp, std::int64_t n)
{
  MPI_Comm node;
  MPI_Comm_split_type(lmp->world, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_on_node = 1;
  MPI_Comm_size(node, &ranks_on_node);
  MPI_Comm_free(&node);
  MPI_Bcast(&ranks_on_node, 1, MPI_INT, 0, lmp->world);
  const double share = static_cast<double>(ranks_on_node) / lmp->comm->nprocs;
  return static_cast<double>(n) * (kDepositionBytesPerSphere + share * kAtomBytesPerSphere);
}

// Memory this machine can still give, in bytes: available memory and free swap of
// /proc/meminfo; a negative value when unknown (not Linux).
double memory_available()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  double kib = 0.0;
  bool found = false;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key;
    double value = 0.0;
    fields >> key >> value;
    if (key == "MemAvailable:" || key == "SwapFree:") {
      kib += value;
      found = found || key == "MemAvailable:";
    }
  }
  return found ? kib * 1024.0 : -1.0;
}

// Refuses, before anything is allocated, a packing that the machine of rank 0 cannot hold: the
// deposition alone would otherwise end in "std::bad_alloc", or be killed when memory runs out.
void check_memory(LAMMPS *lmp, const Request &req, double needed)
{
  double available = lmp->comm->me == 0 ? memory_available() : 0.0;
  MPI_Bcast(&available, 1, MPI_DOUBLE, 0, lmp->world);
  if (available < 0.0 || needed <= available) return;
  // The largest N that fits, rounded down to three significant digits.
  const double fits = std::floor(static_cast<double>(req.params.n) * available / needed);
  const double digits = std::floor(std::log10(std::max(fits, 1.0)));
  const double unit = std::pow(10.0, std::max(0.0, digits - 2.0));
  lmp->error->all(FLERR, "create_packing: N = {} spheres need about {:.3g} GiB of memory where "
                  "MPI rank 0 runs (about {} bytes per sphere for the deposition on rank 0, {} "
                  "per atom for the atoms of the ranks there), but only {:.3g} GiB is available "
                  "(MemAvailable + SwapFree); use a smaller N (here at most about {:.0f})",
                  req.params.n, needed / kGiB, kDepositionBytesPerSphere, kAtomBytesPerSphere,
                  available / kGiB, std::floor(fits / unit) * unit);
}

// The highest centre of the packing (on rank 0), known to every rank.
double highest_centre(LAMMPS *lmp, const tapmc::Packing &packing)
{
  double zmax = -std::numeric_limits<double>::infinity();
  const std::size_t n = packing.radius.size();
  for (std::size_t i = 0; i < n; ++i) zmax = std::max(zmax, packing.xyz[3 * i + 2]);
  MPI_Bcast(&zmax, 1, MPI_DOUBLE, 0, lmp->world);
  return zmax;
}

// A shrink-wrapped top below the highest centre grows to hold the packing (returns whether the
// box changed).
bool grow_open_top(LAMMPS *lmp, const Plan &plan, double zmax)
{
  Domain *domain = lmp->domain;
  if (plan.top_fixed || zmax < domain->boxhi[2]) return false;
  domain->boxhi[2] = zmax + plan.r_max;
  // set_initial_box pads each shrink-wrapped ('s') face by a small fraction of the box again
  // (create_box padded it once): such faces keep their place, so that the floor the styles
  // default to (the lower z bound) is the one the packing was deposited on
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = domain->boxlo[d], hi[d] = domain->boxhi[d];
  domain->set_initial_box();
  for (int d = 0; d < 3; ++d) {
    if (domain->boundary[d][0] == tapmc::kBoundaryShrink) domain->boxlo[d] = lo[d];
    if (domain->boundary[d][1] == tapmc::kBoundaryShrink) domain->boxhi[d] = hi[d];
  }
  domain->set_global_box();
  domain->set_local_box();
  return true;
}

// This rank's atoms (created atoms overwrite ghosts, as in create_atoms); tags follow the
// deposition order after the largest existing tag. Rank 0 holds the packing and broadcasts it
// piece by piece (kPackingBroadcastSpheres); every rank keeps the spheres of its sub-domain.
void create_own_atoms(LAMMPS *lmp, const Request &req, const tapmc::Packing &packing,
                      bool box_changed)
{
  Atom *atom = lmp->atom;
  MPI_Comm world = lmp->world;
  atom->nghost = 0;
  atom->avec->clear_bonus();
  const bigint natoms_before = atom->natoms;
  const int nlocal_before = atom->nlocal;
  tagint max_tag = 0, max_tag_all = 0;
  if (atom->tag_enable)
    for (int i = 0; i < atom->nlocal; ++i) max_tag = std::max(max_tag, atom->tag[i]);
  MPI_Allreduce(&max_tag, &max_tag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);

  const SubDomain mine = my_subdomain(lmp->domain, lmp->comm);
  const bool root = lmp->comm->me == 0;
  std::vector<double> piece;  // x, y, z, r of the spheres first .. first + count - 1
  for (bigint first = 0; first < req.params.n; first += tapmc::defaults::kPackingBroadcastSpheres) {
    const int count = static_cast<int>(
        std::min<bigint>(tapmc::defaults::kPackingBroadcastSpheres, req.params.n - first));
    piece.resize(4 * static_cast<std::size_t>(count));
    if (root)
      for (int k = 0; k < count; ++k) {
        const std::size_t i = static_cast<std::size_t>(first) + k;
        for (int d = 0; d < 3; ++d) piece[4 * k + d] = packing.xyz[3 * i + d];
        piece[4 * k + 3] = packing.radius[i];
      }
    MPI_Bcast(piece.data(), 4 * count, MPI_DOUBLE, 0, world);
    for (int k = 0; k < count; ++k) {
      double x[3] = {piece[4 * k], piece[4 * k + 1], piece[4 * k + 2]};
      if (!mine.owns(x)) continue;
      atom->avec->create_atom(req.type, x);
      const int m = atom->nlocal - 1;
      const double r = piece[4 * k + 3];
      atom->radius[m] = r;
      atom->rmass[m] = req.params.density * (4.0 / 3.0) * tapmc::kPi * r * r * r;
      if (atom->tag_enable) atom->tag[m] = max_tag_all + static_cast<tagint>(first + k) + 1;
    }
  }
  atom->data_fix_compute_variable(nlocal_before, atom->nlocal);

  bigint nlocal = atom->nlocal;
  MPI_Allreduce(&nlocal, &atom->natoms, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (atom->natoms != natoms_before + req.params.n)
    lmp->error->all(FLERR, "create_packing: {} atoms exist after creating {} spheres on top of "
                    "{} (every sphere must have exactly one owner)", atom->natoms,
                    req.params.n, natoms_before);
  if (atom->tag_enable) atom->tag_check();
  if (atom->map_style != Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }
  // Atoms that existed before a box change may now belong to another rank.
  if (box_changed && natoms_before > 0 && lmp->comm->nprocs > 1) {
    Irregular irregular(lmp);
    irregular.migrate_atoms(1);
  }
}

// compute stereo/profile's global measures of the new spheres with its default settings and the
// floor of the deposition, over the deposition area (the whole box without a region, the disk
// of a container): Phi_b,
// <Phi^c>, <Z> and h_s, exactly as that compute reports them for a group of these spheres.
std::string stereo_profile_text(const Plan &plan, const tapmc::Packing &packing)
{
  namespace stereo = tapmc::stereo;
  const stereo::Spheres spheres{packing.xyz.data(), packing.radius.data(), 0.0, nullptr,
                                static_cast<int>(packing.radius.size())};
  stereo::Box box;
  box.lo[0] = plan.dd.xlo;
  box.hi[0] = plan.dd.xhi;
  box.lo[1] = plan.dd.ylo;
  box.hi[1] = plan.dd.yhi;
  box.periodic[0] = plan.dd.periodic_x;
  box.periodic[1] = plan.dd.periodic_y;
  stereo::SummarySettings settings;
  settings.floor = plan.dd.z_floor;
  // in a tube, over the disk (compute stereo/profile with the same container)
  const stereo::Summary s = plan.has_cylinder
                                ? stereo::summarize_cylinder(spheres, plan.cylinder, settings)
                                : stereo::summarize(spheres, box, settings);
  const double bulk_top =
      plan.dd.z_floor + tapmc::defaults::kBulkHeightOverRadius * stereo::mean_radius(spheres);
  // <Z> with four decimals from 1 to 1e6 (lj's beds), else four significant digits: in SI
  // units a bed of 5-micron spheres printed <Z> 0.0000, one of mm beads 0.0080
  const double z = s.mean_height;
  const std::string mean_height = std::fabs(z) >= 1.0 && std::fabs(z) < 1e6
                                      ? fmt::format("{:.4f}", z)
                                      : fmt::format("{:.4g}", z);
  return fmt::format("compute stereo/profile (defaults): Phi_b {:.4f} ({:.4g} <= z <= {:.4g}), "
                     "<Phi^c> {:.4f} ({:.4g} <= z <= {:.4g}), <Z> {}, h_s {:.4g}",
                     s.phi_bulk, plan.dd.z_floor, bulk_top, s.phi_corrected, plan.dd.z_floor,
                     s.top, mean_height, s.surface);
}

// The volume fraction of the packing's interior: the slab from kDepositionBulkMarginOverRadius
// R above the floor to as much below 2 <z - z_floor> (the height of a uniform bed with the same
// mean centre height), away from the floor layers and the rough top.
std::string interior_text(const Request &req, const Plan &plan, const tapmc::Packing &packing)
{
  const double margin = tapmc::defaults::kDepositionBulkMarginOverRadius;
  double z0 = 0.0, z1 = 0.0;
  tapmc::bulk_window(packing, plan.dd, margin * req.params.radius, z0, z1);
  const std::string definition = fmt::format("{:g}R above the floor to {:g}R below twice the "
                                             "mean centre height", margin, margin);
  if (!(z1 - z0 > 2.0 * req.params.radius))
    return "interior volume fraction: none, the slab " + definition + " is thinner than 2R";
  return fmt::format("interior volume fraction {:.4f} ({:.4g} <= z <= {:.4g}: {})",
                     tapmc::slab_volume_fraction(packing, plan.dd, z0, z1), z0, z1, definition);
}

// "x walls, y periodic", or the container's wall.
std::string sides_text(const Plan &plan)
{
  if (plan.has_cylinder)
    return fmt::format("the wall of {} (radius {}, axis x = {}, y = {})", plan.where,
                       plan.cylinder.radius, plan.cylinder.cx, plan.cylinder.cy);
  return fmt::format("x {}, y {}", plan.walls[0] ? "walls" : "periodic",
                     plan.walls[1] ? "walls" : "periodic");
}

void report(LAMMPS *lmp, const Request &req, const Plan &plan, const tapmc::Packing &packing,
            double zmax, double t_deposit)
{
  if (lmp->comm->me == 0) {
    utils::logmesg(lmp,
                   "Created {} spheres by sequential deposition (Jullien-Meakin), sides: {}; "
                   "floor z = {}\n"
                   "  {}\n"
                   "  {}\n"
                   "  highest centre z = {:.6g}; path segments {}, unstable equilibria left {}{}, "
                   "re-drops {}, unresolved {}\n"
                   "  create_packing CPU = {:.3f} seconds\n",
                   req.params.n, sides_text(plan), plan.dd.z_floor,
                   stereo_profile_text(plan, packing), interior_text(req, plan, packing), zmax,
                   packing.stats.segments, packing.stats.perturbations,
                   packing.stats.wedged > 0
                       ? ", wedged at rest " + std::to_string(packing.stats.wedged)
                       : std::string(),
                   packing.stats.redrops,
                   packing.stats.unresolved, t_deposit);
  }
  if (packing.stats.unresolved > 0 && lmp->comm->me == 0)
    lmp->error->warning(FLERR, "create_packing: {} spheres reached the step cap on every drop "
                        "and were left where they stopped (non-overlapping, stability not "
                        "proven)", packing.stats.unresolved);
}

}  // namespace

// parse -> plan the deposition domain -> deposit (on rank 0: the deposition is sequential, and
// no other rank needs the whole packing) -> grow an open top -> create each rank's atoms ->
// report.
void CreatePacking::command(int narg, char **arg)
{
  tapmc::cite_paper(lmp);
  const Request req = parse_request(lmp, narg, arg);
  const Plan plan = plan_domain(lmp, req);
  check_room(lmp, req, plan);
  const double memory_needed = memory_needed_by_rank0_node(lmp, req.params.n);
  check_memory(lmp, req, memory_needed);

  MPI_Barrier(world);
  const double t_start = MPI_Wtime();
  tapmc::Packing packing;
  const std::string style = "create_packing (" + plan.where + ": " +
                            (plan.top_name.empty() ? std::string("open top") : plan.top_name) +
                            ")";
  tapmc::guarded_on_root(lmp, style.c_str(), [&] {
    try {
      packing = tapmc::deposit_packing(req.params.n, req.params.radii(), plan.dd,
                                       static_cast<std::uint64_t>(req.seed));
    } catch (const std::bad_alloc &) {
      throw std::runtime_error(fmt::format(
          "N = {} spheres: rank 0 ran out of memory during the deposition (std::bad_alloc); "
          "it needs about {:.3g} GiB there, more than this process may allocate (ulimit -v, a "
          "batch system's limit); use a smaller N", req.params.n, memory_needed / kGiB));
    }
  });
  const double t_deposit = MPI_Wtime() - t_start;

  const double zmax = highest_centre(lmp, packing);
  tapmc::require_exact_coordinate(lmp, "create_packing", "the packing's top reaches z", 'z',
                                  zmax + plan.r_max, plan.r_smallest);
  const bool box_changed = grow_open_top(lmp, plan, zmax);
  create_own_atoms(lmp, req, packing, box_changed);
  report(lmp, req, plan, packing, zmax, t_deposit);
}
