// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the shared periodic wrap: inside untouched, any distance, image counts, the seam.
#include "tapmc_math.h"

#include <gtest/gtest.h>

#include <cmath>

using tapmc::wrap_periodic;

TEST(Math, WrapLeavesInsideUntouchedAndCountsPeriods)
{
  const double lo = -1.3, hi = 2.9, length = hi - lo;
  int image = 0;
  EXPECT_EQ(wrap_periodic(0.1, lo, hi, length, image), 0.1);
  EXPECT_EQ(wrap_periodic(lo, lo, hi, length, image), lo);
  EXPECT_EQ(image, 0);
  for (int k : {-1000000, -7, -1, 1, 2, 13, 1000000}) {
    for (double x : {lo, -0.4, 0.0, 1.7, std::nextafter(hi, lo)}) {
      int periods = 3;  // the count is added to
      const double shifted = x + k * length;
      const double wrapped = wrap_periodic(shifted, lo, hi, length, periods);
      ASSERT_GE(wrapped, lo);
      ASSERT_LT(wrapped, hi);
      // The unwrapped position is recovered (up to the rounding of x + k L).
      EXPECT_NEAR(wrapped + (periods - 3) * length, shifted, 1e-9 * std::fabs(shifted) + 1e-15)
          << x << " " << k;
      EXPECT_EQ(wrap_periodic(shifted, lo, hi), wrapped);
    }
  }
}

TEST(Math, WrapAtTheSeamLandsOnLo)
{
  // hi itself is lo's image; a point a rounding below lo, whose shift by one length rounds onto
  // hi, lands on lo with no period counted (lo is that point up to the rounding).
  const double lo = 0.0, hi = 10.0;
  int image = 0;
  EXPECT_EQ(wrap_periodic(hi, lo, hi, hi - lo, image), lo);
  EXPECT_EQ(image, 1);
  image = 0;
  const double wrapped = wrap_periodic(-1e-300, lo, hi, hi - lo, image);
  EXPECT_TRUE(wrapped >= lo && wrapped < hi) << wrapped;
  EXPECT_EQ(wrapped, lo);
  EXPECT_EQ(image, 0);
}
