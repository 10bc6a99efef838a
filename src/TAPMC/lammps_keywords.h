// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The optional keywords of a TAPMC style, read from one table: each keyword names how many
// values follow it and what they set. Ranges are not checked here but once, by the kernel's
// validation of the parameters the table filled.
#ifndef TAPMC_LAMMPS_KEYWORDS_H
#define TAPMC_LAMMPS_KEYWORDS_H

#include "error.h"
#include "lammps.h"

#include <functional>
#include <string>

namespace tapmc {

struct Keyword {
  const char *name;
  int nvalues;
  std::function<void(char **values)> parse;  // values: the nvalues arguments after the name
};

// Reads arg[first .. narg) as keyword/values groups of `table`; an unknown keyword or a missing
// value stops with a message naming the style, the keyword and the allowed keywords.
template <std::size_t N>
void parse_keywords(LAMMPS_NS::LAMMPS *lmp, const char *style, const Keyword (&table)[N],
                    int first, int narg, char **arg)
{
  for (int iarg = first; iarg < narg;) {
    const std::string key = arg[iarg];
    const Keyword *found = nullptr;
    for (const Keyword &keyword : table)
      if (key == keyword.name) found = &keyword;
    if (!found) {
      std::string allowed;
      for (const Keyword &keyword : table)
        allowed += (allowed.empty() ? "" : ", ") + std::string(keyword.name);
      lmp->error->all(FLERR, "{}: unknown keyword '{}' (allowed: {})", style, key, allowed);
    }
    if (iarg + found->nvalues >= narg)
      lmp->error->all(FLERR, "{}: keyword '{}' needs {} value(s)", style, key, found->nvalues);
    found->parse(&arg[iarg + 1]);
    iarg += 1 + found->nvalues;
  }
}

}  // namespace tapmc

#endif
