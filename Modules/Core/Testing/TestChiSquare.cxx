#include "ChiSquare.h"
#include "Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

TEST(ChiSquare, QuantilesMatchTables)
{
  // Reference values of chi2inv(p, k).
  EXPECT_NEAR(chiSquareQuantile(0.95, 1), 3.841458820694124, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.95, 2), 5.991464547107979, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.95, 3), 7.814727903251178, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.99, 3), 11.344866730144373, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.5, 10), 9.341817765591966, 1e-9);
  EXPECT_NEAR(chiSquareQuantile(0.001, 2), 0.0020010006671670687, 1e-12);
}

TEST(ChiSquare, CdfInvertsQuantile)
{
  for (int k : { 1, 2, 3, 7 })
  {
    for (double p : { 0.01, 0.3, 0.9, 0.999 })
    {
      EXPECT_NEAR(chiSquareCdf(chiSquareQuantile(p, k), k), p, 1e-12);
    }
  }
  // Two degrees of freedom have the closed form 1 - exp(-x / 2).
  EXPECT_NEAR(chiSquareCdf(4.0, 2), 1.0 - std::exp(-2.0), 1e-14);
}

TEST(ChiSquare, RejectsInvalidArguments)
{
  EXPECT_THROW(chiSquareQuantile(1.0, 3), Error);
  EXPECT_THROW(chiSquareQuantile(0.0, 3), Error);
  EXPECT_THROW(chiSquareQuantile(0.5, 0), Error);
}
