#include "cosim/analysis/bootstrap_errors.h"

#include <gtest/gtest.h>

#include <cmath>

#include "cosim/analysis/growth_fit.h"
#include "synthetic.h"

using namespace cosim::analysis;

namespace {
constexpr double kA1 = 4e-9, kA2 = 1e-9;

ParcelHistories tracked(std::mt19937_64& rng, std::size_t parcels) {
  ParcelHistories h;
  const double dt = 1.0;
  h.mass = test::trackedCoating(rng, parcels, kA1, kA2, dt, 20);
  for (std::size_t s = 0; s < h.mass.size(); ++s) h.time.push_back(dt * static_cast<double>(s + 1));
  return h;
}

GrowthFit fitOf(const ParcelHistories& h) {
  std::vector<CoatingStatistics> stats;
  for (std::size_t s = 0; s < h.time.size(); ++s)
    stats.push_back(coatingStatistics(h.time[s], h.mass[s]));
  return fitGrowth(stats, 0.0, h.time.back());
}
}  // namespace

TEST(BootstrapErrors, MatchTheSpreadOfTrackedBedsWhereRegressionErrorsDoNot) {
  // 150 independent tracked beds of 400 parcels (each parcel a random walk with drift a1 and
  // diffusion a2^2): the spread of the fitted a1 and a2 over the beds is the true standard
  // error. The particle bootstrap of ONE bed must estimate it; the regression (HC3) error,
  // which treats the correlated snapshots as independent, falls far short for a2.
  std::mt19937_64 rng(5);
  const int beds = 150;
  double s1 = 0, s11 = 0, s2 = 0, s22 = 0, boot1 = 0, boot2 = 0, hc2 = 0;
  for (int k = 0; k < beds; ++k) {
    const auto h = tracked(rng, 400);
    const auto f = fitOf(h);
    ASSERT_TRUE(f.ok);
    s1 += f.a1;
    s11 += f.a1 * f.a1;
    s2 += f.a2;
    s22 += f.a2 * f.a2;
    hc2 += f.a2_se;
    const auto b = bootstrapGrowthErrors(h, 0.0, 100, 1000 + static_cast<std::uint64_t>(k));
    ASSERT_TRUE(b.ok) << b.problem;
    boot1 += b.a1_se;
    boot2 += b.a2_se;
  }
  const double spread1 = std::sqrt(s11 / beds - (s1 / beds) * (s1 / beds));
  const double spread2 = std::sqrt(s22 / beds - (s2 / beds) * (s2 / beds));
  RecordProperty("spread_a2", ::testing::PrintToString(spread2));
  RecordProperty("bootstrap_se_a2", ::testing::PrintToString(boot2 / beds));
  RecordProperty("hc3_se_a2", ::testing::PrintToString(hc2 / beds));
  EXPECT_NEAR(boot1 / beds, spread1, 0.2 * spread1);
  EXPECT_NEAR(boot2 / beds, spread2, 0.2 * spread2);
  EXPECT_LT(hc2 / beds, 0.5 * spread2);  // why the bootstrap is needed
}

TEST(BootstrapErrors, AbsentParcelsAreSkippedAndTooLittleDataIsRefused) {
  ParcelHistories h;
  h.time = {1, 2, 3};
  const double nan = std::nan("");
  h.mass = {{1e-9, 2e-9, nan}, {2e-9, 4e-9, 3e-9}, {3e-9, 6e-9, 4.5e-9}};
  const auto b = bootstrapGrowthErrors(h, 0.0, 50);
  EXPECT_TRUE(b.ok) << b.problem;
  EXPECT_EQ(b.parcels, 3u);
  EXPECT_FALSE(bootstrapGrowthErrors(ParcelHistories{{1, 2}, {{1}, {2}}}, 0.0).ok);
}
