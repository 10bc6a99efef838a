// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The only place that knows about LAMMPS version differences (API change of 24 Mar 2022).
// TAPMC_LAMMPS_VERSION is set by CMake from LAMMPSConfigVersion.cmake (e.g. 20210929).
#ifndef TAPMC_LAMMPS_COMPAT_H
#define TAPMC_LAMMPS_COMPAT_H

#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "neighbor.h"

#include <string>

#ifndef TAPMC_LAMMPS_VERSION
#error "TAPMC_LAMMPS_VERSION must be defined (CMake sets it from the LAMMPS package version)"
#endif

#define TAPMC_LAMMPS_NEW_API (TAPMC_LAMMPS_VERSION >= 20220324)

namespace tapmc {
namespace compat {

// Forward communication of a fix's per-atom data (pack/unpack_forward_comm).
inline void forward_comm_fix(LAMMPS_NS::Comm *comm, LAMMPS_NS::Fix *fix)
{
#if TAPMC_LAMMPS_NEW_API
  comm->forward_comm(fix);
#else
  comm->forward_comm_fix(fix);
#endif
}

// Forward communication of a compute's per-atom data (pack/unpack_forward_comm).
inline void forward_comm_compute(LAMMPS_NS::Comm *comm, LAMMPS_NS::Compute *compute)
{
#if TAPMC_LAMMPS_NEW_API
  comm->forward_comm(compute);
#else
  comm->forward_comm_compute(compute);
#endif
}

// Look up a region by ID; nullptr when absent.
inline LAMMPS_NS::Region *find_region(LAMMPS_NS::Domain *domain, const std::string &id)
{
#if TAPMC_LAMMPS_NEW_API
  return domain->get_region_by_id(id);
#else
  const int index = domain->find_region(id);
  return index < 0 ? nullptr : domain->regions[index];
#endif
}

}  // namespace compat
}  // namespace tapmc

#endif
