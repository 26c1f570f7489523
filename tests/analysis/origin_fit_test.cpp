#include "cosim/analysis/origin_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace cosim::analysis;

TEST(OriginFit, HandComputedThreePoints) {
  // x = 1,2,3; y = 2,4,7: b = 31/14; values checked with numpy in a scratch shell:
  // classic se 0.112938487863156, HC3 se 0.231380665653186.
  const auto f = fitThroughOrigin({1, 2, 3}, {2, 4, 7});
  EXPECT_DOUBLE_EQ(f.slope, 31.0 / 14.0);
  EXPECT_NEAR(f.se_classic, 0.112938487863156, 1e-13);
  EXPECT_NEAR(f.se_robust, 0.231380665653186, 1e-13);
  EXPECT_NEAR(f.residuals[2], 7.0 - 3 * 31.0 / 14.0, 1e-14);
}

TEST(OriginFit, ClassicStandardErrorMatchesSpreadForConstantNoise) {
  // y = 2 x + N(0, 0.5^2): the spread of the slope over many draws is sigma / sqrt(sum x^2)
  // and the classic standard error must estimate it.
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<double> x;
  for (int i = 1; i <= 15; ++i) x.push_back(i);
  double sxx = 0;
  for (double v : x) sxx += v * v;
  const int draws = 2000;
  double sum = 0, sum2 = 0, se = 0;
  for (int k = 0; k < draws; ++k) {
    std::vector<double> y;
    for (double v : x) y.push_back(2.0 * v + noise(rng));
    const auto f = fitThroughOrigin(x, y);
    sum += f.slope;
    sum2 += f.slope * f.slope;
    se += f.se_classic;
  }
  const double mean = sum / draws;
  const double spread = std::sqrt(sum2 / draws - mean * mean);
  EXPECT_NEAR(spread, 0.5 / std::sqrt(sxx), 0.05 * 0.5 / std::sqrt(sxx));
  EXPECT_NEAR(se / draws, spread, 0.06 * spread);
  EXPECT_NEAR(mean, 2.0, 4 * spread / std::sqrt(draws));
}

TEST(OriginFit, RefusesDegenerateInput) {
  EXPECT_THROW(fitThroughOrigin({}, {}), std::invalid_argument);
  EXPECT_THROW(fitThroughOrigin({0, 0}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(fitThroughOrigin({1, 2}, {1}), std::invalid_argument);
}
