#include <vimlop/Core/ChiSquare.h>
#include <vimlop/Core/Error.h>

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

TEST(ChiSquare, CdfMatchesClosedFormsForOddAndManyDegrees)
{
  // The normalising Gamma(k / 2) is computed by recurrence (glibc's lgamma
  // is not thread-safe): check it through closed forms, odd and even k.
  for (double x : { 0.5, 3.0, 12.0, 40.0 })
  {
    const double root = std::sqrt(0.5 * x);
    EXPECT_NEAR(chiSquareCdf(x, 1), std::erf(root), 1e-12) << x;
    EXPECT_NEAR(
      chiSquareCdf(x, 3), std::erf(root) - std::sqrt(2.0 * x / M_PI) * std::exp(-0.5 * x), 1e-12)
      << x;
    // Even k: 1 - exp(-x/2) * sum_{i < k/2} (x/2)^i / i!.
    double term = 1.0;
    double sum = 1.0;
    for (int i = 1; i < 15; ++i)
    {
      term *= 0.5 * x / i;
      sum += term;
    }
    EXPECT_NEAR(chiSquareCdf(x, 30), 1.0 - std::exp(-0.5 * x) * sum, 1e-12) << x;
  }
}

TEST(ChiSquare, RejectsInvalidArguments)
{
  EXPECT_THROW(chiSquareQuantile(1.0, 3), Error);
  EXPECT_THROW(chiSquareQuantile(0.0, 3), Error);
  EXPECT_THROW(chiSquareQuantile(0.5, 0), Error);
}
