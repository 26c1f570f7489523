#include "cosim/analysis/extrapolation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.h"

using namespace cosim::analysis;

namespace {
GrowthFit exactFit(double a1, double a2, double t1) {
  std::vector<CoatingStatistics> snaps;
  for (int i = 1; i <= 10; ++i) {
    CoatingStatistics s;
    s.time = t1 * i / 10.0;
    s.count = 10;
    s.mean = a1 * s.time;
    s.variance = a2 * a2 * s.time;
    snaps.push_back(s);
  }
  return fitGrowth(snaps, 0.0, t1);
}
}  // namespace

TEST(Extrapolation, CvFollowsInverseSquareRootWithBand) {
  const auto fit = exactFit(2e-9, 1e-9, 20.0);
  ASSERT_TRUE(fit.ok);
  const auto p = predictCv(fit, 3600.0, 50, 0.2);
  ASSERT_EQ(p.tau.size(), 50u);
  EXPECT_NEAR(p.tau.front(), 2.0, 1e-12);
  EXPECT_NEAR(p.tau.back(), 3600.0, 1e-9);
  // CV(60 min) = (a2/a1)/sqrt(3600) = 0.5/60.
  EXPECT_NEAR(p.cv.back(), 0.5 / 60.0, 1e-12);
  EXPECT_NEAR(p.cv_low.back(), 0.8 * 0.5 / 60.0, 1e-12);
  EXPECT_NEAR(p.cv_high.back(), 1.2 * 0.5 / 60.0, 1e-12);
  const auto d = predictDistribution(fit, 1200.0);
  EXPECT_NEAR(d.mean, 2e-9 * 1200, 1e-18);
  EXPECT_NEAR(d.sigma, 1e-9 * std::sqrt(1200.0), 1e-18);
  EXPECT_NEAR(d.cv, 0.5 / std::sqrt(1200.0), 1e-12);
}

TEST(Extrapolation, PredictionCheckedAgainstLaterSimulatedTimes) {
  // Paper section 4.5: fit the first 20 s, compare to a run going to 75 s.
  std::mt19937_64 rng(21);
  const double a1 = 5e-9, a2 = 1e-9, dt = 2.5;
  const auto masses = test::trackedCoating(rng, 4000, a1, a2, dt, 30);
  std::vector<CoatingStatistics> snaps;
  for (std::size_t s = 0; s < masses.size(); ++s)
    snaps.push_back(coatingStatistics(dt * static_cast<double>(s + 1), masses[s]));
  const auto fit = fitGrowth(snaps, 0.0, 20.0);
  ASSERT_TRUE(fit.ok);
  const auto c = checkPrediction(fit, snaps);
  ASSERT_EQ(c.points.size(), 22u);  // 22.5 .. 75 s
  EXPECT_DOUBLE_EQ(c.points.back().time, 75.0);
  // With 4000 parcels the sampling error of sigma is ~1/sqrt(2*4000) ~ 1 %, of the mean
  // (a2/sqrt(N t))/a1 < 0.1 %; the fit coefficients add a few %.
  EXPECT_LT(c.max_abs_mean_error, 0.01);
  EXPECT_LT(c.max_abs_std_error, 0.08);
  EXPECT_LT(c.max_abs_cv_error, 0.08);
  // The errors are computed as (predicted - simulated)/simulated.
  const auto& p = c.points.back();
  EXPECT_DOUBLE_EQ(p.mean_error, (p.predicted_mean - p.simulated_mean) / p.simulated_mean);
  EXPECT_DOUBLE_EQ(p.predicted_mean, fit.a1 * 75.0);
}
