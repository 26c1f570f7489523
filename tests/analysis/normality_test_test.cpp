#include "cosim/analysis/normality_test.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace cosim::analysis;

// Reference values from scipy 1.10 (scipy.stats.skew, kurtosis(fisher=False), skewtest,
// kurtosistest, normaltest) on the same formula-generated data, computed in a scratch shell.
namespace {
std::vector<double> nearUniform(int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(static_cast<double>((i * 7919) % 1000) / 1000.0);
  return v;
}
}  // namespace

TEST(DagostinoPearson, NearUniformMatchesScipy) {
  const auto t = dagostinoPearson(nearUniform(200));
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.skewness, -0.00973566481741, 1e-11);
  EXPECT_NEAR(t.kurtosis, 1.78696325387, 1e-10);
  EXPECT_NEAR(t.z_skewness, -0.0581484949232, 1e-9);
  EXPECT_NEAR(t.z_kurtosis, -9.97384794887, 1e-9);
  EXPECT_NEAR(t.k2, 99.4810241547, 1e-8);
  EXPECT_NEAR(t.p_value / 2.50017309761e-22, 1.0, 1e-8);
}

TEST(DagostinoPearson, SkewedMatchesScipy) {
  auto v = nearUniform(200);
  for (auto& x : v) x = std::exp(3 * x);
  const auto t = dagostinoPearson(v);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.skewness, 0.956846442235, 1e-10);
  EXPECT_NEAR(t.z_skewness, 4.92754242427, 1e-9);
  EXPECT_NEAR(t.z_kurtosis, -0.521106869609, 1e-9);
  EXPECT_NEAR(t.k2, 24.5522267126, 1e-8);
  EXPECT_NEAR(t.p_value / 4.66177931112e-06, 1.0, 1e-8);
}

TEST(DagostinoPearson, SmallSampleMatchesScipy) {
  std::vector<double> v;
  for (int i = 0; i < 50; ++i) v.push_back(std::sin(0.7 * i) + 0.1 * std::cos(3.1 * i));
  const auto t = dagostinoPearson(v);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.z_skewness, -0.434866498338, 1e-9);
  EXPECT_NEAR(t.z_kurtosis, -5.44298946284, 1e-9);
  EXPECT_NEAR(t.k2, 29.815243164, 1e-8);
  EXPECT_NEAR(t.p_value / 3.35507481242e-07, 1.0, 1e-8);
}

TEST(DagostinoPearson, RefusesTooFewOrIdenticalValues) {
  EXPECT_FALSE(dagostinoPearson(std::vector<double>(10, 1.0)).valid);
  const auto same = dagostinoPearson(std::vector<double>(30, 1.0));
  EXPECT_FALSE(same.valid);
  EXPECT_NE(same.problem.find("same"), std::string::npos);
}
