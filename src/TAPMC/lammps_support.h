// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Helpers shared by the TAPMC styles: exact seed parsing, the guards that turn a kernel
// exception into a LAMMPS error, atom sorting and the ghost shell for runs without a pair style,
// and the check that no two fixes of one style move the same atoms.
#ifndef TAPMC_LAMMPS_SUPPORT_H
#define TAPMC_LAMMPS_SUPPORT_H

#include "tapmc_checks.h"
#include "tapmc_defaults.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "group.h"
#include "lammps.h"
#include "modify.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <string>

namespace tapmc {

// Largest seed: the seeds are 64-bit keys of the random numbers, kept in a signed 64-bit integer.
constexpr std::int64_t kMaxSeed = std::numeric_limits<std::int64_t>::max();

// Whether `s` is written as a whole number: an optional sign and decimal digits, nothing else
// ("1.5", "1e3", "abc" and "" are not).
inline bool integer_text(const std::string &s)
{
  const std::size_t first = !s.empty() && (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if (s.size() == first) return false;
  for (std::size_t k = first; k < s.size(); ++k)
    if (s[k] < '0' || s[k] > '9') return false;
  return true;
}

// A count or seed from its text: a plain decimal integer in [lo, hi] (lo >= 0). Text that is
// no whole number ("1.5", "1e3", "abc") is named as such; a whole number outside the range, or
// too large to read (LAMMPS 2021's inumeric wraps 4294967297 to 1), is named with the range
// and what the range is (`what`).
inline std::int64_t parse_integer(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *name,
                                  const char *text, std::int64_t lo, std::int64_t hi,
                                  const char *what = "an integer")
{
  const std::string s = text;
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!integer_text(s))
    lmp->error->all(FLERR, "{}: {} = {} is not a whole number (allowed range {}, {})", style,
                    name, s, range, what);
  const std::string unsigned_text = s[0] == '+' ? s.substr(1) : s;  // "-5": below any lo
  bool digits = unsigned_text.size() <= 19 && unsigned_text[0] != '-';
  unsigned long long value = 0;
  if (digits) {
    errno = 0;
    value = std::strtoull(unsigned_text.c_str(), nullptr, 10);
    digits = errno == 0;
  }
  if (!digits || value < static_cast<unsigned long long>(lo) ||
      value > static_cast<unsigned long long>(hi))
    lmp->error->all(FLERR, "{}: {} ({})", style, outside_range_message(name, s, range), what);
  return static_cast<std::int64_t>(value);
}

// A whole number that fits a long, from its text; its range is the kernel's to check (its
// validate). Text that is no whole number, or one beyond a long, stops naming the argument.
inline long parse_long(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *name,
                       const char *text)
{
  const std::string s = text;
  if (!integer_text(s))
    lmp->error->all(FLERR, "{}: {} = {} is not a whole number", style, name, s);
  errno = 0;
  const long value = std::strtol(s.c_str(), nullptr, 10);
  if (errno == ERANGE)
    lmp->error->all(FLERR, "{}: {}", style,
                    outside_range_message(name, s,
                                          "[" + std::to_string(std::numeric_limits<long>::min()) +
                                              ", " +
                                              std::to_string(std::numeric_limits<long>::max()) +
                                              "]"));
  return value;
}

// A real number from its text, finite, the whole text read; anything else ("abc", "nan", "inf",
// "1.5x") stops naming the argument and its value (LAMMPS 2021's utils::numeric names neither),
// and the allowed `range` when given. The range of a number is the kernel's to check (its
// validate), after all arguments are read.
inline double parse_real(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *name,
                         const char *text, const std::string &range = "")
{
  const std::string s = text;
  char *end = nullptr;
  const double value = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(value))
    lmp->error->all(FLERR, "{}: {} = {} is not a finite number{}", style, name, s,
                    range.empty() ? "" : " (allowed range " + range + ")");
  return value;
}

// A seed: a plain decimal integer in [1, kMaxSeed] (parse_integer).
inline std::int64_t parse_seed(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *name,
                               const char *text)
{
  return parse_integer(lmp, style, name, text, 1, kMaxSeed);
}

// Runs a kernel call; an exception becomes a LAMMPS error naming the style. `same_on_all_ranks`:
// every rank makes the same call on the same data (then error->all, a clean collective stop),
// otherwise the data are rank-local (error->one).
template <class Call>
void guarded(LAMMPS_NS::LAMMPS *lmp, const char *style, bool same_on_all_ranks, Call &&call)
{
  std::string message;
  try {
    call();
    return;
  } catch (const std::exception &e) {
    message = e.what();
  } catch (...) {
    message = "unknown internal error";
  }
  if (same_on_all_ranks)
    lmp->error->all(FLERR, "{}: {}", style, message);
  else
    lmp->error->one(FLERR, "{}: {}", style, message);
}

// Collective: rank `root`'s text in `text` on every rank (for a message only one rank can write,
// with which every rank then stops: error->all).
inline void broadcast_text(LAMMPS_NS::LAMMPS *lmp, int root, std::string &text)
{
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, lmp->world);
  text.resize(static_cast<std::size_t>(length));
  if (length > 0) MPI_Bcast(&text[0], length, MPI_CHAR, root, lmp->world);
}

// Runs a kernel call on rank 0 only (its result stays there); an exception becomes a LAMMPS error
// on every rank, naming the style (rank 0 broadcasts the message: a clean collective stop).
// Collective.
template <class Call>
void guarded_on_root(LAMMPS_NS::LAMMPS *lmp, const char *style, Call &&call)
{
  std::string message;
  if (lmp->comm->me == 0) {
    try {
      call();
    } catch (const std::exception &e) {
      message = e.what();
      if (message.empty()) message = "unknown internal error";
    } catch (...) {
      message = "unknown internal error";
    }
  }
  broadcast_text(lmp, 0, message);
  if (!message.empty()) lmp->error->all(FLERR, "{}: {}", style, message);
}

// Without a pair style LAMMPS has no neighbour cutoff to size its sort bins, so it disables
// atom sorting itself at every run with the warning "Atom sorting therefore disabled". The
// TAPMC styles need no pair style; they switch sorting off quietly (as 'atom_modify sort 0 0'
// would), unless the user chose a sort bin size. Call from init().
inline void quiet_sorting_without_pair_style(LAMMPS_NS::LAMMPS *lmp)
{
  LAMMPS_NS::Atom *atom = lmp->atom;
  if (!lmp->force->pair && atom->sortfreq > 0 && atom->userbinsize == 0.0) atom->sortfreq = 0;
}

// Largest sphere radius over all atoms and ranks (0 when the atom style has no radius).
// Collective.
inline double largest_radius(LAMMPS_NS::LAMMPS *lmp)
{
  double local = 0.0, all = 0.0;
  const double *radius = lmp->atom->radius;
  if (radius)
    for (int i = 0; i < lmp->atom->nlocal; ++i) local = std::max(local, radius[i]);
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MAX, lmp->world);
  return all;
}

// Smallest sphere radius over all atoms and ranks (+inf without atoms or radii). Collective.
inline double smallest_radius(LAMMPS_NS::LAMMPS *lmp)
{
  double local = std::numeric_limits<double>::infinity(), all = local;
  const double *radius = lmp->atom->radius;
  if (radius)
    for (int i = 0; i < lmp->atom->nlocal; ++i) local = std::min(local, radius[i]);
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MIN, lmp->world);
  return all;
}

// The atom of lowest ID, over all ranks, among the owned atoms i for which `pick(i)` holds, and
// its per-atom radius: (ID, radius), or (-1, 0) when none. Collective: every rank gets both, so
// that all stop with one message naming it.
struct FirstAtom {
  std::int64_t tag;
  double radius;
};
template <class Pick>
FirstAtom first_atom_where(LAMMPS_NS::LAMMPS *lmp, Pick &&pick)
{
  LAMMPS_NS::Atom *atom = lmp->atom;
  double first_tag = std::numeric_limits<double>::infinity();
  for (int i = 0; i < atom->nlocal; ++i)
    if (pick(i)) first_tag = std::min(first_tag, static_cast<double>(atom->tag[i]));
  double first_all = first_tag;
  MPI_Allreduce(&first_tag, &first_all, 1, MPI_DOUBLE, MPI_MIN, lmp->world);
  if (first_all == std::numeric_limits<double>::infinity()) return {-1, 0.0};
  double its_radius = -std::numeric_limits<double>::infinity(), its_all = its_radius;
  for (int i = 0; i < atom->nlocal; ++i)
    if (static_cast<double>(atom->tag[i]) == first_all) its_radius = atom->radius[i];
  MPI_Allreduce(&its_radius, &its_all, 1, MPI_DOUBLE, MPI_MAX, lmp->world);
  return {static_cast<std::int64_t>(first_all), its_all};
}

// A style's radius keyword (fix mc/settle 'diameter', compute stereo/profile and compute
// contacts 'radius') stands for the per-atom radii an atom style without them lacks. Where the
// atoms have radii, the other styles, the dumps and the checks use those: a keyword that differs
// would settle or measure other spheres than the run's (overlaps by the per-atom radii, <Phi^c>
// near 1, silently). Names the first atom (by ID) of the group whose radius differs and the two
// ways out: stops (`stop`: fix mc/settle, which would move the spheres into one another) or
// warns (a compute, whose other radius is a measurement, if a strange one). `keyword_text`: the
// keyword as given ("diameter 0.8"). Collective.
inline void check_radius_keyword_against_atoms(LAMMPS_NS::LAMMPS *lmp, const char *style,
                                               const std::string &keyword_text,
                                               double keyword_radius, int groupbit,
                                               const char *group_name, bool stop)
{
  LAMMPS_NS::Atom *atom = lmp->atom;
  if (!atom->radius_flag || !(keyword_radius > 0.0)) return;
  const double tolerance = defaults::kRadiusMatchTolerance * keyword_radius;
  const FirstAtom differs = first_atom_where(lmp, [&](int i) {
    return (atom->mask[i] & groupbit) && std::fabs(atom->radius[i] - keyword_radius) > tolerance;
  });
  if (differs.tag < 0) return;
  const std::string message = fmt::format(
      "{}: {} gives the spheres radius {}, but atom {} of group {} has per-atom radius {} (atom "
      "style {}): the dumps, the other TAPMC styles and the overlap checks use the per-atom "
      "radii; leave '{}' out (the per-atom radii are used) or give the atoms that radius ('set "
      "group {} diameter {}')",
      style, keyword_text, keyword_radius, differs.tag, group_name, differs.radius,
      atom->atom_style, keyword_text.substr(0, keyword_text.find(' ')), group_name,
      2.0 * keyword_radius);
  if (stop) lmp->error->all(FLERR, message);
  if (lmp->comm->me == 0) lmp->error->warning(FLERR, message);
}

// Hard spheres need no pair style, which leaves LAMMPS with a zero communication cutoff and the
// warning "Communication cutoff is 0.0 ... Atoms may get lost" at every reneighbouring (every
// tap). A style asks here for ghosts `depth` deep: fix mc/settle for what its contacts and
// scheme need; fix tapdilate and compute stereo/profile, which read no ghosts, for one sphere
// diameter (the shell fix mc/settle keeps), so that a run without fix mc/settle is not told
// that atoms may get lost. Never lowers a cutoff set by the user or a pair style. Call from
// init().
inline void request_ghost_depth(LAMMPS_NS::LAMMPS *lmp, double depth)
{
  if (depth > 0.0 && lmp->comm->get_comm_cutoff() < depth) lmp->comm->cutghostuser = depth;
}

// The index of the group whose atoms alone become ghosts ('comm_modify group'; 0, the group
// all: every atom). LAMMPS keeps
// this setting protected in Comm; a pointer to the member, named through a class derived from
// Comm (where it is accessible), reads it from any Comm. Never instantiated.
struct CommBorderGroup : LAMMPS_NS::Comm {
  static int of(const LAMMPS_NS::Comm *comm) { return comm->*(&CommBorderGroup::bordergroup); }
};

// A style that reads ghost atoms (fix mc/settle's domain scheme, compute contacts) needs every
// atom within the depth asked for above. 'comm_modify mode multi' (and multi/old) sizes the
// ghost shell per collection from the pair cutoffs: without a pair style, no ghosts at all (the
// domain scheme let spheres of two sub-domains overlap by 97 % of a diameter). It stops here,
// `loss` naming what would go wrong and `instead` a way out beside the default. 'comm_modify
// group G' sends ghosts of G's atoms only: with atoms the style reads (`read_bits`, a group
// bitmask: every atom for the domain scheme, whose obstacles they all are; its group for
// compute contacts) outside G, the domain scheme moved spheres into them and compute contacts
// missed their contacts, silently. Collective; call from init().
inline void require_ghosts_of_every_atom(LAMMPS_NS::LAMMPS *lmp, const char *style,
                                         const char *loss, const char *instead = "",
                                         int read_bits = 1)
{
  const LAMMPS_NS::Comm *comm = lmp->comm;
  if (comm->mode != LAMMPS_NS::Comm::SINGLE)
    lmp->error->all(FLERR, "{}: 'comm_modify mode {}' gives hard spheres no ghost atoms (LAMMPS "
                    "sizes them from the pair cutoffs, and hard spheres have no pair style), so "
                    "{}: use 'comm_modify mode single' (the default){}", style,
                    comm->mode == LAMMPS_NS::Comm::MULTI ? "multi" : "multi/old", loss, instead);
  const int border_group = CommBorderGroup::of(comm);
  if (border_group == 0) return;
  const int border_bit = lmp->group->bitmask[border_group];
  long outside_local = 0, outside = 0;
  for (int i = 0; i < lmp->atom->nlocal; ++i)
    outside_local += (lmp->atom->mask[i] & read_bits) && !(lmp->atom->mask[i] & border_bit);
  MPI_Allreduce(&outside_local, &outside, 1, MPI_LONG, MPI_SUM, lmp->world);
  if (outside == 0) return;
  const char *name = lmp->group->names[border_group];
  lmp->error->all(FLERR, "{}: 'comm_modify group {}' sends ghost atoms of that group only, and "
                  "{} atoms it reads are outside it, so {}: use 'comm_modify group all' (the "
                  "default){}",
                  style, name, outside, loss, instead);
}

// Two fixes of one style acting on the same atoms would tap (or settle) them twice per step.
// Stops with an error naming both fix IDs, their groups and how many atoms they share when a
// fix of `self`'s style listed before it has a group sharing atoms with `self`'s; fixes on
// disjoint groups are allowed. Collective; call from init().
inline void forbid_same_style_on_shared_atoms(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::Fix *self)
{
  LAMMPS_NS::Modify *modify = lmp->modify;
  for (int k = 0; k < modify->nfix && modify->fix[k] != self; ++k) {
    LAMMPS_NS::Fix *other = modify->fix[k];
    if (std::strcmp(other->style, self->style) != 0) continue;
    const int both = other->groupbit | self->groupbit;
    long local = 0, shared = 0;
    for (int i = 0; i < lmp->atom->nlocal; ++i)
      local += (lmp->atom->mask[i] & both) == both ? 1 : 0;
    MPI_Allreduce(&local, &shared, 1, MPI_LONG, MPI_SUM, lmp->world);
    if (shared > 0)
      lmp->error->all(FLERR,
                      "fix {}: fixes '{}' (group '{}') and '{}' (group '{}') both act on {} "
                      "atom(s), which would be moved twice per step; give each atom one fix {} "
                      "(disjoint groups) or unfix one",
                      self->style, other->id, lmp->group->names[other->igroup], self->id,
                      lmp->group->names[self->igroup], shared, self->style);
  }
}

}  // namespace tapmc

#endif
