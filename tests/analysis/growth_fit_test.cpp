#include "cosim/analysis/growth_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.h"

using namespace cosim::analysis;

namespace {
constexpr double kA1 = 5.4e-9 / 1.0;  // kg/s per parcel (order of the paper's 100 L/min case)
constexpr double kA2 = 1.1e-9;        // kg/s^0.5

GrowthFit fitIndependentDraw(std::mt19937_64& rng, std::size_t parcels) {
  std::vector<CoatingStatistics> snaps;
  for (int i = 1; i <= 20; ++i) {
    const double t = i;
    snaps.push_back(coatingStatistics(t, test::normalCoating(rng, parcels, kA1, kA2, t)));
  }
  return fitGrowth(snaps, 0.0, 20.0);
}
}  // namespace

TEST(GrowthFit, RecoversKnownCoefficientsWithinStandardErrors) {
  std::mt19937_64 rng(7);
  const auto f = fitIndependentDraw(rng, 2000);
  ASSERT_TRUE(f.ok) << f.problem;
  EXPECT_EQ(f.tau.size(), 20u);
  EXPECT_LT(std::abs(f.a1 - kA1), 4 * f.a1_se);
  EXPECT_LT(std::abs(f.a2 - kA2), 4 * f.a2_se);
  EXPECT_LT(f.a1_se, 0.01 * kA1);  // 40k parcel-samples pin a1 to well under 1 %
}

TEST(GrowthFit, StandardErrorsMatchTheSpreadOverRepeatedDraws) {
  std::mt19937_64 rng(11);
  const int draws = 300;
  double s1 = 0, s11 = 0, s2 = 0, s22 = 0, se1 = 0, se2 = 0;
  for (int k = 0; k < draws; ++k) {
    const auto f = fitIndependentDraw(rng, 500);
    ASSERT_TRUE(f.ok);
    s1 += f.a1;
    s11 += f.a1 * f.a1;
    s2 += f.a2;
    s22 += f.a2 * f.a2;
    se1 += f.a1_se;
    se2 += f.a2_se;
  }
  const double m1 = s1 / draws, m2 = s2 / draws;
  const double spread1 = std::sqrt(s11 / draws - m1 * m1);
  const double spread2 = std::sqrt(s22 / draws - m2 * m2);
  // Analytic spread of a1 for this design: Var = sum(t^2 a2^2 t / N) / (sum t^2)^2.
  double st2 = 0, st3 = 0;
  for (int i = 1; i <= 20; ++i) {
    st2 += i * i;
    st3 += i * i * i;
  }
  const double analytic1 = kA2 * std::sqrt(st3 / 500.0) / st2;
  EXPECT_NEAR(spread1, analytic1, 0.1 * analytic1);
  // The HC3 standard errors estimate the spread (300 draws: the spread itself is known to ~4 %).
  EXPECT_NEAR(se1 / draws, spread1, 0.15 * spread1);
  EXPECT_NEAR(se2 / draws, spread2, 0.15 * spread2);
  EXPECT_NEAR(m1, kA1, 4 * spread1 / std::sqrt(draws));
  EXPECT_NEAR(m2, kA2, 4 * spread2 / std::sqrt(draws) + 0.002 * kA2);
}

TEST(GrowthFit, WindowAndCoatingStartSelectSnapshots) {
  std::vector<CoatingStatistics> snaps;
  // Exact data mu = a1 (t - 2), var = a2^2 (t - 2) from t = 2 on.
  for (int i = 0; i <= 10; ++i) {
    CoatingStatistics s;
    s.time = i;
    s.count = 100;
    const double tau = std::max(0.0, i - 2.0);
    s.mean = kA1 * tau;
    s.variance = kA2 * kA2 * tau;
    snaps.push_back(s);
  }
  const auto f = fitGrowth(snaps, 0.0, 8.0, 2.0);
  ASSERT_TRUE(f.ok) << f.problem;
  EXPECT_EQ(f.tau.size(), 6u);  // t = 3..8
  EXPECT_NEAR(f.a1, kA1, 1e-12 * kA1);
  EXPECT_NEAR(f.a2, kA2, 1e-9 * kA2);
  const auto none = fitGrowth(snaps, 9.5, 20.0, 2.0);
  EXPECT_FALSE(none.ok);
  EXPECT_NE(none.problem.find("at least 3"), std::string::npos);
}
