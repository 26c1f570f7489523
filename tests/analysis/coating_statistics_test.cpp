#include "cosim/analysis/coating_statistics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace cosim::analysis;

TEST(CoatingStatistics, HandComputedMoments) {
  // {0, 0, 1, 3}: mean 1, deviations -1 -1 0 2 -> m2 = 6/4, m3 = 6/4, m4 = 18/4.
  const auto s = coatingStatistics(2.0, {0, 0, 1, 3});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 1.0);
  EXPECT_DOUBLE_EQ(s.variance, 1.5);
  EXPECT_DOUBLE_EQ(s.std_dev, std::sqrt(1.5));
  EXPECT_DOUBLE_EQ(s.cv, std::sqrt(1.5));
  EXPECT_DOUBLE_EQ(s.skewness, 1.5 / std::pow(1.5, 1.5));
  EXPECT_DOUBLE_EQ(s.excess_kurtosis, 4.5 / 2.25 - 3.0);
  EXPECT_DOUBLE_EQ(s.total, 4.0);
  EXPECT_DOUBLE_EQ(s.uncoated_share, 0.5);  // the two zeros
  EXPECT_DOUBLE_EQ(s.min, 0.0);
  EXPECT_DOUBLE_EQ(s.max, 3.0);
}

TEST(CoatingStatistics, UncoatedThresholdIsRelativeToTheMean) {
  // mean = 1e-9; threshold 1e-6 * mean = 1e-15: 5e-16 counts as uncoated, 2e-15 does not.
  const auto s = coatingStatistics(1.0, {5e-16, 2e-15, 1e-9 - 2.5e-15 + 1e-9, 1e-9 + 1e-9}, 1e-6);
  EXPECT_DOUBLE_EQ(s.uncoated_share, 0.25);
  const auto none = coatingStatistics(0.0, {0, 0, 0});
  EXPECT_DOUBLE_EQ(none.uncoated_share, 1.0);
  EXPECT_TRUE(std::isnan(none.cv));
}

TEST(CoatingStatistics, EmptySnapshot) {
  const auto s = coatingStatistics(1.0, {});
  EXPECT_EQ(s.count, 0u);
  EXPECT_TRUE(std::isnan(s.mean));
}
