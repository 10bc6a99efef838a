// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// fix tapdilate against the stock displace_atoms reference (the same homothety written with an
// atom-style variable), constant and variable eps, on any number of MPI ranks.
#include "tapmc_test_util.h"

#include "library.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

// 300 atoms at random positions in a 10 x 10 x 12 box with a floor at z = 0.5, the processor
// grid split along z (so that taps move atoms across sub-domains on several ranks).
std::vector<std::string> random_atoms_setup()
{
  int nprocs = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  const std::string procs = "1 1 " + std::to_string(nprocs);
  return {"units lj",
          "atom_style sphere",
          "boundary p p fm",
          "processors " + procs,
          "region box block 0 10 0 10 0 12",
          "create_box 1 box",
          "region inside block 0 10 0 10 0.5 12",
          "create_atoms 1 random 300 4821 inside",
          "set group all diameter 0.5",
          "thermo_modify lost error"};
}

std::vector<double> positions_by_tag(LAMMPS_NS::LAMMPS *lmp)
{
  const int n = static_cast<int>(lammps_get_natoms(lmp));
  std::vector<double> x(3 * static_cast<size_t>(n));
  lammps_gather_atoms(lmp, const_cast<char *>("x"), 1, 3, x.data());
  return x;
}

void expect_same_positions(const std::vector<double> &a, const std::vector<double> &b)
{
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    ASSERT_NEAR(a[k], b[k], 1e-12 * (1.0 + std::fabs(b[k]))) << "coordinate " << k;
}

}  // namespace

// Run on 1 rank (ctest unit of the library API tests) and under mpirun with 2 and 4 ranks; the
// processor grid splits z, so taps move atoms across sub-domains.
TEST(MpiTapDilate, ConstantEpsMatchesDisplaceAtoms)
{
  auto tapped = tapmc_test::make_lammps();
  tapmc_test::run_lines(tapped.get(), random_atoms_setup());
  tapmc_test::run_lines(tapped.get(), {"fix tap all tapdilate 0.3 floor 0.5", "run 4"});

  auto reference = tapmc_test::make_lammps();
  tapmc_test::run_lines(reference.get(), random_atoms_setup());
  tapmc_test::run_lines(reference.get(), {"variable dz atom 0.3*(z-0.5)"});
  for (int tap = 0; tap < 4; ++tap)
    tapmc_test::run_lines(reference.get(), {"displace_atoms all move 0 0 v_dz units box"});

  EXPECT_EQ(lammps_get_natoms(tapped.get()), 300.0);
  expect_same_positions(positions_by_tag(tapped.get()), positions_by_tag(reference.get()));
}

// eps from an equal-style variable, evaluated on each tap's timestep, tapping every 2 steps.
TEST(MpiTapDilate, VariableEpsEveryTwoSteps)
{
  auto tapped = tapmc_test::make_lammps();
  tapmc_test::run_lines(tapped.get(), random_atoms_setup());
  tapmc_test::run_lines(tapped.get(), {"variable e equal 0.01*step",
                                       "fix tap all tapdilate v_e every 2 floor 0.5", "run 6"});

  auto reference = tapmc_test::make_lammps();
  tapmc_test::run_lines(reference.get(), random_atoms_setup());
  for (int step : {2, 4, 6})
    tapmc_test::run_lines(reference.get(),
                          {"variable dz atom " + std::to_string(0.01 * step) + "*(z-0.5)",
                           "displace_atoms all move 0 0 v_dz units box"});
  expect_same_positions(positions_by_tag(tapped.get()), positions_by_tag(reference.get()));

  // The fix reports the latest eps and sqrt(eps) (excitation strength, paper eq. 2).
  auto *eps = static_cast<double *>(lammps_extract_fix(tapped.get(), "tap", 0, 0, 0, 0));
  ASSERT_NE(eps, nullptr);
  EXPECT_NEAR(*eps, 0.06, 1e-15);
  lammps_free(eps);
  // [1] eps, [2] sqrt(eps); an index beyond (the library does not check it) is NaN, not a read
  // of whatever memory follows
  const double expected[] = {0.06, std::sqrt(0.06)};
  for (int n = 0; n < 4; ++n) {
    auto *value = static_cast<double *>(lammps_extract_fix(tapped.get(), "tap", 0, 1, n, 0));
    ASSERT_NE(value, nullptr);
    if (n < 2) EXPECT_NEAR(*value, expected[n], 1e-15) << n;
    else EXPECT_TRUE(std::isnan(*value)) << n << ": " << *value;
    lammps_free(value);
  }
}

// Only the group is dilated; the rest stays where it was.
TEST(MpiTapDilate, GroupOnly)
{
  auto lmp = tapmc_test::make_lammps();
  tapmc_test::run_lines(lmp.get(), random_atoms_setup());
  tapmc_test::run_lines(lmp.get(), {"group low id <= 150"});
  const auto before = positions_by_tag(lmp.get());
  tapmc_test::run_lines(lmp.get(), {"fix tap low tapdilate 0.1 floor 0.5", "run 1"});
  const auto after = positions_by_tag(lmp.get());
  for (int i = 0; i < 300; ++i) {
    const double z0 = before[3 * i + 2];
    const double expected = i < 150 ? 0.5 + (z0 - 0.5) * 1.1 : z0;
    ASSERT_NEAR(after[3 * i + 2], expected, 1e-12) << "atom " << i + 1;
    ASSERT_EQ(after[3 * i], before[3 * i]);
  }
}
