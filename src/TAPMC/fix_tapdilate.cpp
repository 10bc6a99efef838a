// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix tapdilate: the tap of the model, a homothetic vertical dilation about the floor.
#include "fix_tapdilate.h"

#include "lammps_box.h"
#include "lammps_citation.h"
#include "lammps_container.h"
#include "lammps_keywords.h"
#include "lammps_relocate.h"
#include "lammps_support.h"
#include "tapmc_dilation.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "utils.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

FixTapDilate::FixTapDilate(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), eps_var_index(-1), last_eps(0.0), tapped_step(-1)
{
  tapmc::cite_paper(lmp);
  if (narg < 4)
    error->all(FLERR, "fix tapdilate: expected 'fix ID group tapdilate eps [every N] "
               "[floor z0] [container region-ID]', got {} argument(s)", narg);

  params.z_floor = domain->boxlo[2];
  if (std::strncmp(arg[3], "v_", 2) == 0) {
    eps_variable = arg[3] + 2;  // params.eps stays 0 here; each tap checks the variable's value
    if (eps_variable.empty())  // init() would look up no variable: every tap at eps = 0
      error->all(FLERR, "fix tapdilate: eps = v_ names no variable (give a number, or v_name "
                 "of an equal-style variable)");
  } else {
    params.eps = tapmc::parse_real(lmp, "fix tapdilate", "eps", arg[3]);
  }

  const tapmc::Keyword table[] = {
      {"every", 1,
       [&](char **v) {
         params.every = tapmc::parse_integer(lmp, "fix tapdilate", "every", v[0], 1,
                                             std::numeric_limits<int>::max());
       }},
      {"floor", 1,
       [&](char **v) { params.z_floor = tapmc::parse_real(lmp, "fix tapdilate", "floor", v[0]); }},
      {tapmc::kContainerKeyword, 1, [&](char **v) { container_region_id = v[0]; }},
  };
  tapmc::parse_keywords(lmp, "fix tapdilate", table, 4, narg, arg);
  tapmc::guarded(lmp, "fix tapdilate", true, [&] { tapmc::validate(params); });

  tapmc::require_box_with_floor(lmp, "fix tapdilate");
  resolve_container(0.0);  // the radii may not be set yet: init() checks them

  // Moves happen in pre_exchange() of steps on which this fix forces reneighbouring.
  force_reneighbor = 1;
  // The tap is what moves the atoms from step to step (LAMMPS from 2023 on warns "No fixes with
  // time integration, atoms won't move" when no fix says so).
  time_integrate = 1;
  next_reneighbor = -1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 2;
  extscalar = 0;
  extvector = 0;
  global_freq = 1;
  restart_global = 1;
}

int FixTapDilate::setmask()
{
  return PRE_EXCHANGE | POST_INTEGRATE | END_OF_STEP;
}

// Computes read before this step's move (an eps variable's) computed again for the packing
// after it (lammps_relocate.h): one loop over the computes per step.
void FixTapDilate::end_of_step()
{
  tapmc::refresh_moved_computes(lmp);
}

void FixTapDilate::init()
{
  tapmc::quiet_sorting_without_pair_style(lmp);
  tapmc::request_ghost_depth(lmp, 2.0 * tapmc::largest_radius(lmp));
  tapmc::forbid_same_style_on_shared_atoms(lmp, this);
  tapmc::require_box_with_floor(lmp, "fix tapdilate");  // change_box may have made it another
  // the region may have been deleted or redefined, the box changed, the radii set
  resolve_container(atom->radius_flag ? tapmc::largest_radius(lmp) : 0.0);
  const double r_min = atom->radius_flag ? tapmc::smallest_radius(lmp) : 0.0;
  exact_z_bound = r_min > 0.0 ? tapmc::largest_exact_coordinate(2.0 * r_min)
                              : std::numeric_limits<double>::infinity();
  if (!eps_variable.empty()) {
    eps_var_index = input->variable->find(eps_variable.c_str());
    if (eps_var_index < 0)
      error->all(FLERR, "fix tapdilate: variable '{}' for eps does not exist", eps_variable);
    if (!input->variable->equalstyle(eps_var_index))
      error->all(FLERR, "fix tapdilate: variable '{}' for eps must be equal-style",
                 eps_variable);
  }
}

// The container, checked as every TAPMC style checks it (lammps_container.h); the tap itself
// never reads it. max_sphere_radius <= 0 skips the check of the spheres' size. Collective.
void FixTapDilate::resolve_container(double max_sphere_radius)
{
  if (!container_region_id.empty())
    tapmc::resolve_container(lmp, "fix tapdilate", container_region_id, max_sphere_radius);
}

void FixTapDilate::schedule_next_tap()
{
  next_reneighbor = next_tap_after(update->ntimestep);
}

void FixTapDilate::setup_pre_exchange()
{
  tapped_step = -1;
  check_geometry();
  schedule_next_tap();
}

// Every step, before LAMMPS decides whether to reneighbour (and so whether pre_exchange runs):
// the tap steps again from the step before. A run with 'pre no' calls no setup hook, and after
// reset_timestep the last run's schedule never (or late) met the new steps: the run went on
// without tapping. A fix no run has set up stays unscheduled, for fix mc/settle to refuse.
void FixTapDilate::post_integrate()
{
  if (!scheduled()) return;
  const bigint now = update->ntimestep;
  if (tapped_step >= now) tapped_step = -1;  // the steps were reset back
  next_reneighbor = next_tap_after(now - 1);
}

// Atoms of the group must sit above the floor; the dilation would otherwise push them down.
void FixTapDilate::check_geometry()
{
  double **x = atom->x;
  const int *mask = atom->mask;
  double zmin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < atom->nlocal; ++i)
    if (mask[i] & groupbit) zmin = std::min(zmin, x[i][2]);
  double zmin_all;
  MPI_Allreduce(&zmin, &zmin_all, 1, MPI_DOUBLE, MPI_MIN, world);
  if (zmin_all < params.z_floor)
    error->all(FLERR, "fix tapdilate: an atom centre is at z = {} below the floor z0 = {}; "
               "set 'floor' at or below the lowest atom", zmin_all, params.z_floor);
}

double FixTapDilate::current_eps()
{
  if (eps_var_index < 0) return params.eps;
  modify->clearstep_compute();
  tapmc::DilationParams now = params;
  now.eps = input->variable->compute_equal(eps_var_index);
  modify->addstep_compute(update->ntimestep + params.every);
  const std::string style =
      fmt::format("fix tapdilate (variable '{}', step {})", eps_variable, update->ntimestep);
  tapmc::guarded(lmp, style.c_str(), true, [&] { tapmc::validate(now); });
  return now.eps;
}

bigint FixTapDilate::next_tap_after(bigint step) const
{
  return (step / params.every) * params.every + params.every;
}

bool FixTapDilate::tapped_this_step() const
{
  return tapped_step == update->ntimestep;
}

void FixTapDilate::pre_exchange()
{
  tap_if_due();
}

void FixTapDilate::tap_if_due()
{
  if (update->ntimestep != next_reneighbor || tapped_this_step()) return;
  tapped_step = update->ntimestep;
  last_eps = current_eps();
  schedule_next_tap();
  if (last_eps == 0.0) return;

  // Where the tap puts the highest sphere top, checked before moving anything: a fixed upper z
  // boundary would silently lose atoms, and beyond exact_z_bound contacts are not resolved.
  double top = -std::numeric_limits<double>::infinity();
  double **x = atom->x;
  const double *radius = atom->radius;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double r = radius ? radius[i] : 0.0;
    top = std::max(top, tapmc::dilated_height(x[i][2], params.z_floor, last_eps) + r);
  }
  double top_all;
  MPI_Allreduce(&top, &top_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (domain->boundary[2][1] == tapmc::kBoundaryFixed && top_all > domain->boxhi[2])
    error->all(FLERR, "fix tapdilate: the tap on step {} lifts atoms to z = {} above the fixed "
               "upper z boundary {}; use an open (shrink-wrapped) top, 'm' or 's' "
               "('boundary p p fm' or 'f f fs'), or a higher box", update->ntimestep, top_all, domain->boxhi[2]);
  // A bed rising tap after tap: spheres the redeposition left high (its stop rule compares the
  // change of <Z> with eta <Z>, which a few high spheres make large) are lifted by eps each tap
  // until doubles no longer resolve a contact. Stop by name, not with lost atoms later.
  if (top_all > exact_z_bound)
    error->all(FLERR, "fix tapdilate: the tap on step {} lifts a sphere to z = {}, beyond |z| = "
               "{:.3g} where doubles cannot resolve the contacts of the smallest spheres: the "
               "bed has come apart (spheres that the redeposition left high rise by eps at "
               "every tap; a tighter eta or 'stop drift' of fix mc/settle brings them back)",
               update->ntimestep, top_all, exact_z_bound);

  if (atom->nlocal > 0)
    tapmc::dilate_about_floor(&atom->x[0][0], atom->mask, groupbit, atom->nlocal,
                              params.z_floor, last_eps);
  tapmc::relocate_moved_atoms(lmp, "fix tapdilate");
}

double FixTapDilate::compute_scalar()
{
  return last_eps;
}

// [1] eps of the latest tap, [2] sqrt(eps): the excitation strength (paper, eq. 2).
double FixTapDilate::compute_vector(int n)
{
  if (n == 0) return last_eps;
  // thermo and variables check the index; the library interface (extract_fix) does not
  return n == 1 ? std::sqrt(last_eps) : std::numeric_limits<double>::quiet_NaN();
}

// The restart record is the eps of the latest tap (one double): a run resumed from the file
// outputs it until its own first tap, as the run that wrote the file would have (fix print of
// the restart step, thermo). A file without the record leaves 0, the value before any tap.
void FixTapDilate::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const int size = sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(&last_eps, sizeof(double), 1, fp);
}

void FixTapDilate::restart(char *buf)
{
  std::memcpy(&last_eps, buf, sizeof(double));
}
