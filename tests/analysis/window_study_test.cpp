#include "cosim/analysis/window_study.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace cosim::analysis;

TEST(WindowStudy, ExactGrowthGivesTheSameFitForEveryWindowAndWallTimesInterpolate) {
  const double a1 = 3e-9, a2 = 1.5e-9;
  std::vector<CoatingStatistics> snaps;
  for (int i = 1; i <= 40; ++i) {
    CoatingStatistics s;
    s.time = 0.5 * i;
    s.count = 100;
    s.mean = a1 * s.time;
    s.variance = a2 * a2 * s.time;
    s.std_dev = std::sqrt(s.variance);
    s.cv = s.std_dev / s.mean;
    snaps.push_back(s);
  }
  TimeSeries ts;
  ts.columns = {"time", "wall_seconds"};
  ts.values = {{0.0, 20.0}, {0.0, 50.0}};  // 2.5 s of wall time per simulated second
  const auto w = studyFitWindow(snaps, 0.0, 0.0, 1200.0, &ts);
  ASSERT_EQ(w.points.size(), 9u);
  EXPECT_DOUBLE_EQ(w.run_end, 20.0);
  EXPECT_DOUBLE_EQ(w.points.front().t_end, 4.0);  // 20 % of the run
  EXPECT_DOUBLE_EQ(w.points.front().wall_seconds, 10.0);
  EXPECT_DOUBLE_EQ(w.points.back().t_end, 20.0);
  EXPECT_DOUBLE_EQ(w.points.back().wall_seconds, 50.0);
  for (const auto& p : w.points) {
    ASSERT_TRUE(p.ok);
    EXPECT_NEAR(p.a1, a1, 1e-12 * a1);
    EXPECT_NEAR(p.a2, a2, 1e-9 * a2);
    EXPECT_NEAR(p.cv_horizon, 0.5 / std::sqrt(1200.0), 1e-9);
  }
  EXPECT_NEAR(w.points.front().cv_run_end_error, 0.0, 1e-9);
  EXPECT_TRUE(
      std::isnan(w.points.back().cv_run_end_error));  // the full window predicts nothing new
}

TEST(WindowStudy, ShortWindowOfADriftingRunShowsItsError) {
  // The variance grows as t^1.5 instead of t: a fit on the first 20 % underestimates the CV
  // at the end by a known factor. Fit of v = c t^1.5 through the origin on t = 1..4 gives
  // slope b = c sum(t^2.5)/sum(t^2); predicted CV(20)/true CV(20) = sqrt(b 20 / (c 20^1.5)).
  std::vector<CoatingStatistics> snaps;
  for (int i = 1; i <= 20; ++i) {
    CoatingStatistics s;
    s.time = i;
    s.count = 100;
    s.mean = 1.0 * i;
    s.variance = 0.01 * std::pow(i, 1.5);
    s.std_dev = std::sqrt(s.variance);
    s.cv = s.std_dev / s.mean;
    snaps.push_back(s);
  }
  const auto w = studyFitWindow(snaps, 0.0, 0.0, 1200.0);
  const auto& p = w.points.front();  // window [0, 4]
  ASSERT_TRUE(p.ok);
  double s25 = 0, s2 = 0;
  for (int i = 1; i <= 4; ++i) {
    s25 += std::pow(i, 2.5);
    s2 += i * i;
  }
  const double ratio = std::sqrt(s25 / s2 * 20.0 / std::pow(20.0, 1.5));
  EXPECT_NEAR(p.cv_run_end_error, ratio - 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(p.wall_seconds));
}
