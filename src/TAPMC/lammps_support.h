// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Helpers shared by the TAPMC styles: exact seed parsing, the guards that turn a kernel
// exception into a LAMMPS error, and atom sorting for runs without a pair style.
#ifndef TAPMC_LAMMPS_SUPPORT_H
#define TAPMC_LAMMPS_SUPPORT_H

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lammps.h"

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>

namespace tapmc {

// Largest seed: the seeds are 64-bit keys of the random numbers, kept in a signed 64-bit integer.
constexpr std::int64_t kMaxSeed = std::numeric_limits<std::int64_t>::max();

// A seed from its text: a plain decimal integer in [1, kMaxSeed]; anything else (a sign, a
// fraction, an exponent, a value that would saturate) stops with a message naming the value.
inline std::int64_t parse_seed(LAMMPS_NS::LAMMPS *lmp, const char *style, const char *name,
                               const char *text)
{
  const std::string s = text;
  bool digits = !s.empty() && s.size() <= 19;
  for (char c : s) digits = digits && c >= '0' && c <= '9';
  unsigned long long value = 0;
  if (digits) {
    errno = 0;
    value = std::strtoull(s.c_str(), nullptr, 10);
    digits = errno == 0;
  }
  if (!digits || value < 1 || value > static_cast<unsigned long long>(kMaxSeed))
    lmp->error->all(FLERR, "{}: {} = {} must be a positive integer in [1, {}]", style, name, s,
                    kMaxSeed);
  return static_cast<std::int64_t>(value);
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

}  // namespace tapmc

#endif
