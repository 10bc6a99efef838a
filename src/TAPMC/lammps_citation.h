// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The paper every TAPMC style implements, registered with LAMMPS's citation reminder.
#ifndef TAPMC_LAMMPS_CITATION_H
#define TAPMC_LAMMPS_CITATION_H

#include "citeme.h"
#include "lammps.h"

namespace tapmc {

// LAMMPS's citation format: one line (what the terse reminder on the screen shows), a blank
// line, then the BibTeX entry (what the log file and log.cite get). All five styles add the same
// text, so a run that uses several of them lists the paper once.
inline constexpr char kPaperCitation[] =
    "TAPMC package (fix tapdilate, fix mc/settle, compute stereo/profile, compute contacts, "
    "create_packing): "
    "doi:10.1103/PhysRevE.63.051304\n\n"
    "@Article{Philippe01,\n"
    " author = {P. Philippe and D. Bideau},\n"
    " title = {Numerical model for granular compaction under vertical tapping},\n"
    " journal = {Phys.\\ Rev.\\ E},\n"
    " year = 2001,\n"
    " volume = 63,\n"
    " number = 5,\n"
    " pages = {051304},\n"
    " doi = {10.1103/PhysRevE.63.051304}\n"
    "}\n\n";

// Adds the paper to the run's citations (once per run; nothing with -nocite, where LAMMPS has no
// CiteMe). Every TAPMC style calls it when it is created, as LAMMPS's own styles do.
inline void cite_paper(LAMMPS_NS::LAMMPS *lmp)
{
  if (lmp->citeme) lmp->citeme->add(kPaperCitation);
}

}  // namespace tapmc

#endif
