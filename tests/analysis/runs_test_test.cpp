#include "cosim/analysis/runs_test.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace cosim::analysis;

TEST(RunsTest, TwoLongRunsAreStructured) {
  // ++++----: n+ = n- = 4, R = 2, expected 5, var 2*16*24/(64*7) = 12/7;
  // z = -3/sqrt(12/7), p = Phi(z) = 0.010973385501623417 (scipy.stats.norm.cdf).
  const auto r = runsTest({1, 2, 3, 4, -1, -2, -3, -4});
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.runs, 2u);
  EXPECT_DOUBLE_EQ(r.expected_runs, 5.0);
  EXPECT_NEAR(r.z, -3.0 / std::sqrt(12.0 / 7.0), 1e-14);
  EXPECT_NEAR(r.p_too_few, 0.010973385501623417, 1e-14);
}

TEST(RunsTest, AlternatingSignsAreNotStructuredAndZerosAreDropped) {
  const auto r = runsTest({1, 0, -1, 1, -1, 1, -1, 1, -1});
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.runs, 8u);
  EXPECT_NEAR(r.p_too_few, 1.0 - 0.010973385501623417, 1e-14);
  EXPECT_FALSE(runsTest({1, 2, 3}).valid);
}
