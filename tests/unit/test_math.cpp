// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// Tests of the shared periodic wrap: inside untouched, any distance, image counts, the seam.
#include "tapmc_checks.h"
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

// Every kernel refuses a parameter in one phrase, quoting doubles in their shortest round-trip
// form and integers exactly (also beyond 2^53, where a double would round them).
TEST(Checks, OnePhraseAndOneWayToWriteValues)
{
  auto message = [](auto value) {
    try {
      tapmc::throw_outside_range("x", value, "(0, 1]");
    } catch (const std::invalid_argument &e) {
      return std::string(e.what());
    }
    return std::string("(no exception)");
  };
  EXPECT_EQ(message(-0.1), "x = -0.1 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(1e300), "x = 1e+300 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(std::nan("")), "x = nan is outside the allowed range (0, 1]");
  EXPECT_EQ(message(0.1 + 0.2), "x = 0.30000000000000004 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(10.0), "x = 10 is outside the allowed range (0, 1]");  // not "1e+01"
  EXPECT_EQ(message(1500.0), "x = 1500 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(1e6), "x = 1e+06 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(-0.0), "x = -0 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(-5), "x = -5 is outside the allowed range (0, 1]");
  EXPECT_EQ(message(9007199254740993LL),
            "x = 9007199254740993 is outside the allowed range (0, 1]");
  EXPECT_EQ(tapmc::outside_range_message("seed", "1.5", "[1, 10]"),
            "seed = 1.5 is outside the allowed range [1, 10]");
}
