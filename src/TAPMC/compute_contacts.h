// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute contacts: coordination number of every sphere within a gap, its mean and distribution.
#ifndef LMP_COMPUTE_CONTACTS_H
#define LMP_COMPUTE_CONTACTS_H

#include "compute.h"

#include "tapmc_contacts.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeContacts : public Compute {
 public:
  ComputeContacts(class LAMMPS *, int, char **);
  ~ComputeContacts() override;
  void init() override;
  void compute_peratom() override;
  void compute_vector() override;
  void compute_array() override;
  double memory_usage() override;

 private:
  tapmc::contacts::Settings settings_;
  tapmc::contacts::Counter counter_;
  double fixed_radius_;  // radius keyword (> 0), or 0: per-atom radius
  int nmax_;             // length of vector_atom
  std::vector<int> owned_;                 // owned atoms of the group (local indices)
  std::vector<double> xyz_, radius_;       // owned atoms of the group, then ghosts of the group
  std::vector<int> counts_;                // per owned atom of the group
  std::vector<unsigned char> on_floor_;    // per owned atom of the group

  void parse_arguments(int narg, char **arg);
  double group_radius_max();
  double ghost_depth_needed(double r_max) const;
  void check_ghost_shell(double r_max);
  void count();
  void summarize();
};

}  // namespace LAMMPS_NS

#endif
