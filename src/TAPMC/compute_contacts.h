// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute contacts: coordination number of every sphere within a gap, its mean and distribution.
#ifndef LMP_COMPUTE_CONTACTS_H
#define LMP_COMPUTE_CONTACTS_H

#include "compute.h"

#include "lammps_container.h"
#include "tapmc_contacts.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeContacts : public Compute, public tapmc::ContainerHolder {
 public:
  ComputeContacts(class LAMMPS *, int, char **);
  ~ComputeContacts() override;
  void init() override;
  void compute_peratom() override;
  void compute_vector() override;
  void compute_array() override;
  double memory_usage() override;
  // the group's bit of each owned atom to its ghosts (a dynamic group, see count())
  int pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc) override;
  void unpack_forward_comm(int n, int first, double *buf) override;
  // tapmc::ContainerHolder, for fix mc/settle's check of one container per run. Without
  // 'container' the compute counts contacts between spheres only, in a tube too (as without
  // 'floor' it leaves out the floor): a choice, not a mismatch.
  const std::string &container_region() const override { return container_id_; }
  bool container_optional() const override { return true; }
  bool bed_floor(double &z0) const override
  {
    z0 = settings_.floor_z;
    return settings_.floor;
  }
  bool keyword_radius(double &radius) const override
  {
    radius = fixed_radius_;
    return fixed_radius_ > 0.0;
  }

 private:
  tapmc::contacts::Settings settings_;
  tapmc::contacts::Counter counter_;
  double fixed_radius_;  // radius keyword (> 0), or 0: per-atom radius
  int nmax_;             // length of vector_atom
  // The step whose counts counts_ holds (-1: none since the run's init): the per-atom vector,
  // the vector and the array read on one step share one count, unless a move since (fix
  // tapdilate, fix mc/settle) marked the stamps stale (counts_current()).
  bigint counted_step_ = -1;
  std::vector<int> owned_;                 // owned atoms of the group (local indices)
  std::vector<double> xyz_, radius_;       // owned atoms of the group, then ghosts of the group
  std::vector<int> counts_;                // per owned atom of the group
  std::vector<unsigned char> on_floor_;    // per owned atom of the group
  std::vector<unsigned char> on_wall_;     // per owned atom of the group
  std::string container_id_;               // 'container' region ID; empty: no wall counted

  void parse_arguments(int narg, char **arg);
  void resolve_container(double max_sphere_radius);
  double group_radius_max(bool any_atom_may_join = false);
  double ghost_depth_needed(double r_max) const;
  void check_ghost_shell(double r_max);
  bool counts_current() const;
  void count();
  void summarize();
};

}  // namespace LAMMPS_NS

#endif
