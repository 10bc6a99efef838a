// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute stereo/profile: exact stereological packing fractions (Phi_b, <Phi^c>, <Z>, profiles).
#ifndef LMP_COMPUTE_STEREO_PROFILE_H
#define LMP_COMPUTE_STEREO_PROFILE_H

#include "compute.h"

#include "lammps_container.h"
#include "tapmc_cylinder.h"
#include "tapmc_stereology.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeStereoProfile : public Compute, public tapmc::ContainerHolder {
 public:
  ComputeStereoProfile(class LAMMPS *, int, char **);
  ~ComputeStereoProfile() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  double memory_usage() override;
  // tapmc::ContainerHolder, for fix mc/settle's check of one container per run.
  const std::string &container_region() const override { return container_id_; }
  bool bed_floor(double &z0) const override
  {
    z0 = settings_.floor;
    return true;
  }
  bool side_walls(int dim, double &lo, double &hi) const override;
  bool keyword_radius(double &radius) const override
  {
    radius = fixed_radius_;
    return fixed_radius_ > 0.0;
  }

 private:
  tapmc::stereo::SummarySettings settings_;
  tapmc::stereo::PlaneGrid planes_;
  int axis_;                  // profile direction: 0 x, 1 y, 2 z, 3 r (radial: with a container)
  double fixed_radius_;       // radius keyword (> 0), or 0: per-atom radius
  double mean_radius_;        // R used by the defaults (fixed radius or group mean at init)
  double group_count_;        // atoms in the group when mean_radius_ was computed
  bool radius_ready_;         // mean_radius_ computed (init, or first use before any run)
  bool floor_warned_;         // the below-the-floor warning was given in this run
  bool central_warned_;       // the empty-central-zone warning was given (once per compute)
  bool window_warned_;        // the empty-window warning was given for the vector (once)
  bool profile_window_warned_ = false;  // ... for the array's profile of vertical cuts
  std::vector<int> selected_; // owned atoms of the group, rebuilt per invocation
  std::vector<double> buffer_;
  std::string container_id_;  // 'container' region ID; empty: the box is the container
  tapmc::Cylinder cylinder_;  // the container, resolved at definition and in init()

  bool parse_keywords(int narg, char **arg);
  bool has_container() const { return !container_id_.empty(); }
  void resolve_container();
  void check_axis();
  void update_mean_radius();
  bool group_is_empty();
  void warn_below_floor();
  void warn_empty_central_zone(const tapmc::stereo::Windows &, const tapmc::stereo::Box &);
  void warn_empty_window(double lo, double hi, bool &warned, const std::string &what);
  void warn_empty_core(const tapmc::stereo::Windows &);
  bool ready_to_measure();
  void compute_vector_guarded();
  void compute_array_guarded();
  tapmc::stereo::Spheres select_spheres();
  tapmc::stereo::Box current_box() const;
  tapmc::stereo::Box measure_box() const;
  double reduce_surface_height(const tapmc::stereo::Spheres &, const tapmc::stereo::Box &);
};

}  // namespace LAMMPS_NS

#endif
