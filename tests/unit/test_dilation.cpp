// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the tap kernel: the homothety about the floor and the validation of its parameters.
#include "tapmc_defaults.h"
#include "tapmc_dilation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace {
std::string message_of(const tapmc::DilationParams &params)
{
  try {
    tapmc::validate(params);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "(no exception)";
}
}  // namespace

TEST(Dilation, HeightsAboveTheFloorGrowByOnePlusEps)
{
  double xyz[6] = {1.0, 2.0, 3.0, 4.0, 5.0, 0.5};
  const int mask[2] = {1, 0};
  EXPECT_EQ(tapmc::dilate_about_floor(xyz, mask, 1, 2, 0.5, 0.2), 0.5 + 2.5 * 1.2);
  EXPECT_EQ(xyz[2], tapmc::dilated_height(3.0, 0.5, 0.2));
  EXPECT_EQ(xyz[0], 1.0);
  EXPECT_EQ(xyz[5], 0.5);  // not in the group
}

TEST(Dilation, ParamsValidationNamesTheParameter)
{
  tapmc::DilationParams good;
  good.eps = tapmc::defaults::kMaxTapEps;
  EXPECT_NO_THROW(tapmc::validate(good));
  tapmc::DilationParams p = good;
  p.eps = -0.1;
  EXPECT_EQ(message_of(p), "eps = -0.1 is outside the allowed range [0, 1] (relative dilation of "
                           "the heights above the floor; eps = 1 doubles them)");
  p.eps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of(p).find("eps = nan is outside the allowed range [0, 1]"), std::string::npos);
  p = good;
  p.every = 0;
  EXPECT_EQ(message_of(p), "every = 0 is outside the allowed range [1, +inf)");
  p = good;
  p.z_floor = INFINITY;
  EXPECT_EQ(message_of(p), "floor = inf is outside the allowed range (finite)");
}
