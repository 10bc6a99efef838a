// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute stereo/profile through the library API: FCC lattice analytic values, and the compute
// against the LAMMPS-free kernel on the same positions (groups, walls, mixed radii, radius keyword).
#include "tapmc_test_util.h"

#include "library.h"
#include "tapmc_stereology.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

const double kPi = std::acos(-1.0);
const double kFcc = kPi / (3.0 * std::sqrt(2.0));
constexpr double kA = 2.0;  // FCC cell (metal units: lattice fcc 2.0), spheres at contact

// 4 x 4 x 8 FCC cells (512 spheres, layers every a/2 = 1 from z = 0 to 15) in a box 8 x 8 x 20.
std::vector<std::string> fcc_setup(const std::string &boundary, const std::string &style = "sphere",
                                   const std::string &lattice_region = "0 4 0 4 0 7.9")
{
  std::vector<std::string> lines = {"units metal",
                                    "atom_style " + style,
                                    "boundary " + boundary,
                                    "lattice fcc 2.0",
                                    "region box block 0 4 0 4 0 10",
                                    "create_box 1 box",
                                    "region latt block " + lattice_region,
                                    "create_atoms 1 region latt"};
  if (style != "sphere") lines.push_back("mass 1 1.0");
  if (style == "sphere") {
    lines.push_back("set group all diameter 1.4142135623730951");
    lines.push_back("set group all density 1.0");
  }
  return lines;
}

std::vector<double> vector_of(LAMMPS_NS::LAMMPS *lmp, const char *id)
{
  auto *v = static_cast<double *>(
      lammps_extract_compute(lmp, const_cast<char *>(id), LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR));
  return std::vector<double>(v, v + 7);
}

std::vector<double> array_of(LAMMPS_NS::LAMMPS *lmp, const char *id, int rows)
{
  auto **a = static_cast<double **>(
      lammps_extract_compute(lmp, const_cast<char *>(id), LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY));
  std::vector<double> out;
  for (int k = 0; k < rows; ++k) out.insert(out.end(), a[k], a[k] + 3);
  return out;
}

// The owned atoms of a serial instance, as the kernel sees them.
struct Snapshot {
  std::vector<double> xyz, radius;
  tapmc::stereo::Box box;
  tapmc::stereo::Spheres spheres(const std::vector<int> *index = nullptr) const
  {
    tapmc::stereo::Spheres s;
    s.xyz = xyz.data();
    s.radius = radius.data();
    s.count = static_cast<int>(radius.size());
    if (index) {
      s.index = index->data();
      s.count = static_cast<int>(index->size());
    }
    return s;
  }
};

Snapshot snapshot(LAMMPS_NS::LAMMPS *lmp, bool periodic_xy)
{
  Snapshot s;
  const int n = static_cast<int>(lammps_get_natoms(lmp));
  s.xyz.resize(3 * static_cast<size_t>(n));
  lammps_gather_atoms(lmp, const_cast<char *>("x"), 1, 3, s.xyz.data());
  s.radius.resize(n);
  lammps_gather_atoms(lmp, const_cast<char *>("radius"), 1, 1, s.radius.data());
  double lo[3], hi[3], xy, yz, xz;
  int periodicity[3], changed;
  lammps_extract_box(lmp, lo, hi, &xy, &yz, &xz, periodicity, &changed);
  for (int d = 0; d < 3; ++d) {
    s.box.lo[d] = lo[d];
    s.box.hi[d] = hi[d];
  }
  s.box.periodic[0] = s.box.periodic[1] = periodic_xy;
  return s;
}

void expect_vector_matches(const std::vector<double> &v, const tapmc::stereo::Summary &s)
{
  const double expected[7] = {s.phi_bulk,    s.phi_corrected, s.mean_height, s.top,
                              s.phi_lateral, s.phi_central,   s.surface};
  for (int i = 0; i < 7; ++i) {
    if (std::isnan(expected[i]))  // no central zone (lateral zones meeting at the middle)
      EXPECT_TRUE(std::isnan(v[i])) << i << " " << v[i];
    else
      EXPECT_NEAR(v[i], expected[i], 1e-12 * (1.0 + std::fabs(expected[i]))) << i;
  }
}

}  // namespace

TEST(ComputeStereoProfile, FccLatticeGivesAnalyticValues)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p f"));
  const double r = kA / (2.0 * std::sqrt(2.0));
  const double surface = 7.5 * kA + r;
  // window [2, 10] and the bulk slab [2, 6]: whole periods inside the lattice
  char top_fraction[32];
  std::snprintf(top_fraction, sizeof top_fraction, "%.17g", 8.0 / (surface - 2.0));
  tapmc_test::run_lines(
      lmp.get(), {"compute phi all stereo/profile floor 2.0 bulk 4.0 wall_factor 1.0 column 2.0 "
                  "lateral 2.0 window 4.0 12.0 top_fraction " + std::string(top_fraction),
                  "thermo_style custom step c_phi[1] c_phi[2]", "run 0"});
  const std::vector<double> v = vector_of(lmp.get(), "phi");
  EXPECT_NEAR(v[0], kFcc, 1e-12);
  EXPECT_NEAR(v[1], kFcc, 1e-12);
  EXPECT_NEAR(v[2], 7.5 - 2.0, 1e-12);  // layers at z = 0, 1, ..., 15, equal populations
  EXPECT_NEAR(v[3], 10.0, 1e-12);
  EXPECT_NEAR(v[4], kFcc, 1e-12);
  EXPECT_NEAR(v[5], kFcc, 1e-12);
  EXPECT_NEAR(v[6], surface, 1e-12);
}

TEST(ComputeStereoProfile, FccProfilesAlongZXAndY)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p f"));
  tapmc_test::run_lines(lmp.get(),
                        {"compute pz all stereo/profile planes 2.0 10.0 4",
                         "compute px all stereo/profile axis x planes 0.0 8.0 4 window 4.0 12.0",
                         "compute py all stereo/profile axis y planes 0.0 8.0 8 window 4.0 12.0",
                         "run 0"});
  const std::vector<double> z = array_of(lmp.get(), "pz", 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(z[3 * k], 3.0 + 2.0 * k, 1e-14);
    EXPECT_NEAR(z[3 * k + 1], kPi / 4.0, 1e-12);  // planes through (001) layers
    EXPECT_NEAR(z[3 * k + 2], kFcc, 1e-12);
  }
  const std::vector<double> x = array_of(lmp.get(), "px", 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(x[3 * k + 2], kFcc, 1e-12);
  // y bins of half a period: pairs of neighbouring bins average to the FCC fraction
  const std::vector<double> y = array_of(lmp.get(), "py", 8);
  for (int k = 0; k < 8; k += 2) EXPECT_NEAR(0.5 * (y[3 * k + 2] + y[3 * k + 5]), kFcc, 1e-12);
}

TEST(ComputeStereoProfile, MatchesKernelOnPerturbedPackingsWithGroupsAndWalls)
{
  for (const char *boundary : {"p p f", "f f f"}) {
    const bool periodic = std::string(boundary) == "p p f";
    auto lmp = tapmc_test::make_lammps();
    // lattice points kept off the faces, so that random displacements lose no atom at walls
    tapmc_test::run_lines(lmp.get(), fcc_setup(boundary, "sphere", "0.1 3.9 0.1 3.9 0.1 7.9"));
    tapmc_test::run_lines(
        lmp.get(), {"displace_atoms all random 0.15 0.15 0.15 4711 units box",
                    "region low block INF INF INF INF INF 9.0 units box",
                    "group low region low",
                    "set group low diameter 1.2",  // mixed radii: defaults use the mean radius
                    "compute all all stereo/profile floor 0.5",
                    "compute low low stereo/profile floor 0.5 top_fraction 0.8 lateral 1.5",
                    "compute zx all stereo/profile axis x planes -0.5 8.5 37",
                    "compute zz all stereo/profile planes 0.0 16.0 50",
                    "run 0"});
    const Snapshot snap = snapshot(lmp.get(), periodic);
    std::vector<int> low;
    for (int i = 0; i < static_cast<int>(snap.radius.size()); ++i)
      if (snap.xyz[3 * i + 2] <= 9.0) low.push_back(i);
    ASSERT_GT(low.size(), 100u);
    ASSERT_LT(low.size(), snap.radius.size());

    tapmc::stereo::SummarySettings set;
    set.floor = 0.5;
    expect_vector_matches(vector_of(lmp.get(), "all"),
                          tapmc::stereo::summarize(snap.spheres(), snap.box, set));
    set.top_fraction = 0.8;
    set.lateral_width = 1.5;
    const std::vector<double> v_low = vector_of(lmp.get(), "low");
    expect_vector_matches(v_low, tapmc::stereo::summarize(snap.spheres(&low), snap.box, set));
    for (int i : {0, 1, 4, 5}) EXPECT_GT(v_low[i], 0.1) << i;  // every zone holds spheres

    // profile along x, default window [floor + 2R, z_top] from the group's data
    tapmc::stereo::SummarySettings def;
    def.floor = snap.box.lo[2];
    const tapmc::stereo::Summary s = tapmc::stereo::summarize(snap.spheres(), snap.box, def);
    const double mean_r = tapmc::stereo::mean_radius(snap.spheres());
    const std::vector<double> zx = tapmc::stereo::profile(
        snap.spheres(), snap.box, 0, {-0.5, 8.5, 37}, def.floor + 2.0 * mean_r, s.top);
    const std::vector<double> x = array_of(lmp.get(), "zx", 37);
    for (size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], zx[i], 1e-12) << boundary << " " << i;
    const std::vector<double> zz =
        tapmc::stereo::profile(snap.spheres(), snap.box, 2, {0.0, 16.0, 50}, 0.0, 0.0);
    const std::vector<double> z = array_of(lmp.get(), "zz", 50);
    for (size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(z[i], zz[i], 1e-12) << boundary << " " << i;
  }
}

TEST(ComputeStereoProfile, RadiusKeywordWithAtomStyleAtomic)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p f", "atomic"));
  tapmc_test::run_lines(lmp.get(), {"compute phi all stereo/profile floor 2.0 bulk 4.0 radius "
                                    "0.70710678118654752",
                                    "run 0"});
  const std::vector<double> v = vector_of(lmp.get(), "phi");
  EXPECT_NEAR(v[0], kFcc, 1e-12);
  EXPECT_NEAR(v[2], 5.5, 1e-12);
}

TEST(ComputeStereoProfile, ThermoAndTimeAverageSeeTheOutputs)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p f"));
  tapmc_test::run_lines(lmp.get(),
                        {"compute phi all stereo/profile floor 2.0 bulk 4.0",
                         "compute pz all stereo/profile planes 2.0 10.0 4",
                         "variable phib equal c_phi[1]",
                         "fix av all ave/time 1 2 2 c_pz[*] mode vector",
                         "thermo_style custom step v_phib", "run 2"});
  // the equal-style variable reads the compute that thermo invoked on the last step
  auto *phib = static_cast<double *>(
      lammps_extract_variable(lmp.get(), const_cast<char *>("phib"), nullptr));
  ASSERT_NE(phib, nullptr);
  EXPECT_NEAR(*phib, kFcc, 1e-12);
  lammps_free(phib);
  // fix ave/time's global array: row k = time average of the compute's row k
  for (int k = 0; k < 4; ++k) {
    auto *value = static_cast<double *>(
        lammps_extract_fix(lmp.get(), const_cast<char *>("av"), LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, k, 2));
    EXPECT_NEAR(*value, kFcc, 1e-12) << k;
    lammps_free(value);
  }
}

TEST(ComputeStereoProfile, ContainerMatchesTheCylinderKernel)
{
  // A jostled simple-cubic bed in a tube (some spheres poke through the wall by up to ~0.1):
  // the vector, Phi(z) over the disk and the radial profile equal the kernel's on the same
  // positions, with the container recovered from the region as typed.
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(
      lmp.get(), {"units lj", "atom_style sphere", "boundary f f fm",
                  "region box block 0 12 0 12 0 14", "create_box 1 box",
                  "region tube cylinder z 6.25 5.75 5.5 EDGE EDGE units box",
                  "region inner cylinder z 6 6 5.0 0.5 8.5 units box", "lattice sc 1.0",
                  "create_atoms 1 region inner", "set group all diameter 1.0",
                  "displace_atoms all random 0.05 0.05 0.05 4711 units box",
                  "compute phi all stereo/profile container tube floor 0.0",
                  "compute pz all stereo/profile container tube planes 0.0 10.0 40",
                  "compute pr all stereo/profile container tube axis r planes 0.0 5.5 22",
                  "run 0"});
  const Snapshot snap = snapshot(lmp.get(), false);
  const tapmc::Cylinder tube{6.25, 5.75, 5.5};
  tapmc::stereo::SummarySettings set;
  set.floor = 0.0;
  const tapmc::stereo::Summary s = tapmc::stereo::summarize_cylinder(snap.spheres(), tube, set);
  const std::vector<double> v = vector_of(lmp.get(), "phi");
  expect_vector_matches(v, s);
  for (int i : {0, 1, 4, 5}) EXPECT_GT(v[i], 0.3) << i;
  // the material beyond the wall is not counted: below the box's whole-sphere value over the disk
  EXPECT_LT(v[0], tapmc::stereo::horizontal_slab_volume(snap.spheres(), 0.0, 2.0) /
                      (kPi * 5.5 * 5.5 * 2.0));

  const std::vector<double> z =
      tapmc::stereo::cylinder_profile(snap.spheres(), tube, {0.0, 10.0, 40});
  const std::vector<double> pz = array_of(lmp.get(), "pz", 40);
  for (size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(pz[i], z[i], 1e-12) << i;
  const std::vector<double> r =
      tapmc::stereo::radial_profile(snap.spheres(), tube, {0.0, 5.5, 22}, 1.0, s.top);
  const std::vector<double> pr = array_of(lmp.get(), "pr", 22);
  for (size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(pr[i], r[i], 1e-12) << i;
}
