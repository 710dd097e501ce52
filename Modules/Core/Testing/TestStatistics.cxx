#include <vimlop/Core/Statistics.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace vimlop;

TEST(Statistics, SummaryOfASample)
{
  const Summary s = summarize({ 4.0, 1.0, 3.0, 2.0 });
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  // Linear interpolation between ranks: 3 + 0.85 and 3 + 0.97 of the last step.
  EXPECT_DOUBLE_EQ(s.p95, 3.85);
  EXPECT_DOUBLE_EQ(s.p99, 3.97);
  EXPECT_DOUBLE_EQ(summarize({}).mean, 0.0);
}

TEST(Statistics, RocAucCountsOrderedPairsAndHalfTies)
{
  EXPECT_DOUBLE_EQ(rocAuc({ 5.0, 6.0 }, { 1.0, 2.0 }), 1.0);
  EXPECT_DOUBLE_EQ(rocAuc({ 1.0, 2.0 }, { 5.0, 6.0 }), 0.0);
  // 3 > 1, 3 > 2, 3 = 3 (half), 1 < 2, 1 = 1 (half), 1 < 3: 3 of 6.
  EXPECT_DOUBLE_EQ(rocAuc({ 3.0, 1.0 }, { 1.0, 2.0, 3.0 }), 3.0 / 6.0);
  EXPECT_TRUE(std::isnan(rocAuc({}, { 1.0 })));
}

TEST(Statistics, BestThresholdSeparatesTheGroups)
{
  EXPECT_DOUBLE_EQ(bestSeparatingThreshold({ 10.0, 12.0, 20.0 }, { 1.0, 2.0, 4.0 }), 7.0);
  // One negative above one positive: the threshold keeps most of both right.
  const double t = bestSeparatingThreshold({ 3.0, 10.0, 12.0 }, { 1.0, 2.0, 11.0 });
  EXPECT_DOUBLE_EQ(t, 2.5);
  EXPECT_TRUE(std::isnan(bestSeparatingThreshold({ 1.0 }, {})));
}
