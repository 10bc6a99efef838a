// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// compute contacts through the library API, on any number of MPI ranks (tests named Mpi* run
// again on 2 and 4 ranks): an FCC lattice made by LAMMPS (12 contacts, a gap sweep), and the
// compute against the LAMMPS-free counter on the gathered packing (periodic axes instead of
// ghosts) for a perturbed lattice with mixed radii, a group and a floor.
#include "tapmc_test_util.h"

#include "atom.h"
#include "library.h"
#include "tapmc_contacts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

namespace contacts = tapmc::contacts;

// 4 x 4 x 4 FCC cells of side 2 (metal units: lattice fcc 2.0), spheres at contact
// (R = 1/sqrt 2), the processor grid as LAMMPS chooses it.
std::vector<std::string> fcc_setup(const std::string &boundary, const std::string &lattice_region)
{
  return {"units metal",
          "atom_style sphere",
          "atom_modify map array",
          "boundary " + boundary,
          "lattice fcc 2.0",
          "region box block 0 4 0 4 0 4",
          "create_box 1 box",
          "region latt block " + lattice_region,
          "create_atoms 1 region latt",
          "set group all diameter 1.4142135623730951",
          "set group all density 1.0"};
}

std::vector<double> vector_of(LAMMPS_NS::LAMMPS *lmp, const char *id)
{
  auto *v = static_cast<double *>(
      lammps_extract_compute(lmp, const_cast<char *>(id), LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR));
  return std::vector<double>(v, v + 6);
}

std::vector<double> distribution_of(LAMMPS_NS::LAMMPS *lmp, const char *id)
{
  auto **a = static_cast<double **>(
      lammps_extract_compute(lmp, const_cast<char *>(id), LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY));
  std::vector<double> out;
  for (int z = 0; z < contacts::kHistogramRows; ++z) {
    EXPECT_EQ(a[z][0], z);
    out.push_back(a[z][1]);
  }
  return out;
}

// The per-atom counts of this rank's atoms, as (tag, count).
std::vector<std::pair<long, int>> owned_counts(LAMMPS_NS::LAMMPS *lmp, const char *id)
{
  auto *c = static_cast<double *>(
      lammps_extract_compute(lmp, const_cast<char *>(id), LMP_STYLE_ATOM, LMP_TYPE_VECTOR));
  std::vector<std::pair<long, int>> out;
  for (int i = 0; i < lmp->atom->nlocal; ++i) {
    EXPECT_EQ(c[i], std::floor(c[i]));
    out.emplace_back(static_cast<long>(lmp->atom->tag[i]), static_cast<int>(c[i]));
  }
  return out;
}

}  // namespace

TEST(MpiComputeContacts, FccLatticeHasTwelveThenEighteen)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p p", "INF INF INF INF INF INF"));
  tapmc_test::run_lines(lmp.get(), {"compute touch all contacts 0.0",
                                    "compute near all contacts 0.4",
                                    "compute second all contacts 0.42",
                                    "thermo_style custom step c_touch[1] c_second[1]", "run 0"});
  ASSERT_EQ(lammps_get_natoms(lmp.get()), 256.0);
  for (const char *id : {"touch", "near", "second"}) {
    const int expected = std::string(id) == "second" ? 18 : 12;
    for (const auto &tc : owned_counts(lmp.get(), id)) ASSERT_EQ(tc.second, expected) << id;
    const std::vector<double> v = vector_of(lmp.get(), id);
    EXPECT_EQ(v, (std::vector<double>{double(expected), 0.0, 0.0, 0.0, double(expected), 0.0}))
        << id;
    std::vector<double> p(contacts::kHistogramRows, 0.0);
    p[expected] = 1.0;
    EXPECT_EQ(distribution_of(lmp.get(), id), p) << id;
  }
}

// A perturbed lattice with mixed radii above a floor, periodic sides: the compute (ghost atoms,
// any rank count) against the counter on the whole gathered packing (periodic x and y), for all
// atoms, for a group (atoms outside it neither count nor are counted), and with the floor.
TEST(MpiComputeContacts, MatchesTheCounterOnTheGatheredPacking)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), fcc_setup("p p f", "0 4 0 4 0.1 3.9"));
  tapmc_test::run_lines(
      lmp.get(), {"displace_atoms all random 0.1 0.1 0.1 4711 units box",
                  "region low block INF INF INF INF INF 4.5 units box", "group low region low",
                  "set group low diameter 1.35",
                  "compute all all contacts 0.02 floor 0.3",
                  "compute low low contacts 0.05",
                  "compute fixed all contacts 0.01 radius 0.7",
                  "run 0"});
  const int n = static_cast<int>(lammps_get_natoms(lmp.get()));
  std::vector<double> xyz(3 * static_cast<size_t>(n)), radius(n), tags(n);
  lammps_gather_atoms(lmp.get(), const_cast<char *>("x"), 1, 3, xyz.data());
  lammps_gather_atoms(lmp.get(), const_cast<char *>("radius"), 1, 1, radius.data());
  contacts::Box box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = 8.0;
    box.periodic[d] = d < 2;
  }
  std::vector<int> low;
  for (int i = 0; i < n; ++i)
    if (xyz[3 * i + 2] <= 4.5) low.push_back(i);
  ASSERT_GT(low.size(), 50u);
  ASSERT_LT(low.size(), static_cast<size_t>(n));

  struct Case {
    const char *id;
    contacts::Settings settings;
    std::vector<int> members;  // indices (tag - 1) of the group
    double fixed_radius;
  };
  std::vector<int> everyone(n);
  for (int i = 0; i < n; ++i) everyone[i] = i;
  contacts::Settings all_settings, low_settings, fix_settings;
  all_settings.gap = 0.02;
  all_settings.floor = true;
  all_settings.floor_z = 0.3;
  low_settings.gap = 0.05;
  fix_settings.gap = 0.01;
  const Case cases[] = {{"all", all_settings, everyone, 0.0},
                        {"low", low_settings, low, 0.0},
                        {"fixed", fix_settings, everyone, 0.7}};
  for (const Case &c : cases) {
    std::vector<double> sub_xyz, sub_radius;
    for (int i : c.members) {
      sub_xyz.insert(sub_xyz.end(), {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
      sub_radius.push_back(c.fixed_radius > 0.0 ? c.fixed_radius : radius[i]);
    }
    contacts::Spheres s;
    s.xyz = sub_xyz.data();
    s.radius = sub_radius.data();
    s.count = static_cast<int>(sub_radius.size());
    std::vector<int> expected(s.count);
    std::vector<unsigned char> floor(s.count);
    contacts::Counter().count(s, s.count, box, c.settings, expected.data(), floor.data());
    std::vector<int> by_tag(n, 0);
    for (size_t k = 0; k < c.members.size(); ++k) by_tag[c.members[k]] = expected[k];
    for (const auto &tc : owned_counts(lmp.get(), c.id))
      ASSERT_EQ(tc.second, by_tag[tc.first - 1]) << c.id << " atom " << tc.first;

    double sums[contacts::kNumSums] = {};
    const int largest =
        contacts::accumulate(expected.data(), floor.data(), nullptr, nullptr, s.count, sums);
    const contacts::Distribution d = contacts::finish(sums, largest);
    const std::vector<double> v = vector_of(lmp.get(), c.id);
    EXPECT_NEAR(v[0], d.mean, 1e-12) << c.id;
    EXPECT_NEAR(v[1], d.fraction_none, 1e-14) << c.id;
    EXPECT_NEAR(v[2], d.fraction_few, 1e-14) << c.id;
    EXPECT_NEAR(v[3], d.fraction_floor, 1e-14) << c.id;
    EXPECT_EQ(v[4], d.max) << c.id;
    EXPECT_EQ(v[5], 0.0) << c.id;  // no container: no wall contact
    const std::vector<double> p = distribution_of(lmp.get(), c.id);
    for (int z = 0; z < contacts::kHistogramRows; ++z)
      EXPECT_NEAR(p[z], d.fraction[z], 1e-14) << c.id << " Z = " << z;
    EXPECT_GT(d.mean, 1.0) << c.id;  // the gaps catch contacts
  }
  // some spheres of the bottom layer (z - R from 0.225 to 0.425) touch the floor at 0.3
  const double on_floor = vector_of(lmp.get(), "all")[3];
  EXPECT_GT(on_floor, 0.0);
  EXPECT_LT(on_floor, 0.25);
}

TEST(ComputeContacts, RadiusKeywordWithAtomStyleAtomic)
{
  auto lmp = tapmc_test::make_lammps();
  std::vector<std::string> lines = fcc_setup("p p p", "INF INF INF INF INF INF");
  lines.resize(9);  // no per-atom diameter: atom_style atomic
  lines[1] = "atom_style atomic";
  lines.push_back("mass 1 1.0");
  tapmc_test::run_lines(lmp.get(), lines);
  tapmc_test::run_lines(lmp.get(),
                        {"compute c all contacts 0.001 radius 0.70710678118654752", "run 0"});
  EXPECT_EQ(vector_of(lmp.get(), "c")[0], 12.0);
}
