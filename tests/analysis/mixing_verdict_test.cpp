#include "cosim/analysis/mixing_verdict.h"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.h"

using namespace cosim::analysis;

namespace {
constexpr double kA1 = 5e-9, kA2 = 1e-9;

struct SyntheticRun {
  std::vector<CoatingStatistics> stats;
  std::vector<double> last;
};

SyntheticRun trackedRun(std::uint64_t seed, double uncoated_share) {
  std::mt19937_64 rng(seed);
  SyntheticRun r;
  const double dt = 0.5;
  const auto masses = test::trackedCoating(rng, 3000, kA1, kA2, dt, 40, uncoated_share);
  for (std::size_t s = 0; s < masses.size(); ++s) {
    r.stats.push_back(coatingStatistics(dt * static_cast<double>(s + 1), masses[s]));
  }
  r.last = masses.back();
  return r;
}

// Every parcel coated, mean and variance linear in t, but coating masses exponential-like:
// a1 t - theta + Exponential(theta), theta = a2 sqrt(t): mean a1 t, variance a2^2 t, skewness 2,
// excess kurtosis 6.
SyntheticRun skewedRun() {
  std::mt19937_64 rng(9);
  SyntheticRun r;
  for (int i = 1; i <= 20; ++i) {
    const double t = i;
    std::gamma_distribution<double> g(1.0, kA2 * std::sqrt(t));
    std::vector<double> m(3000);
    for (auto& x : m) x = kA1 * t - kA2 * std::sqrt(t) + g(rng);
    r.stats.push_back(coatingStatistics(t, m));
    r.last = m;
  }
  return r;
}

// A bed of parcels that pass through the coating zone (synthetic.h, passCoating), snapshots every
// 0.5 s to 20 s, with its history for the verdict.
struct PassRun {
  std::vector<CoatingStatistics> stats;
  std::vector<double> last;
  NormalityHistory history;
};
PassRun passRun(std::uint64_t seed, double rate, double slow_share = 0, double slow_rate = 0) {
  std::mt19937_64 rng(seed);
  PassRun r;
  const double dt = 0.5;
  const auto masses = test::passCoating(rng, 4000, rate, 1e-10, dt, 40, slow_share, slow_rate);
  for (std::size_t s = 0; s < masses.size(); ++s)
    r.stats.push_back(coatingStatistics(dt * static_cast<double>(s + 1), masses[s]));
  r.last = masses.back();
  r.history.snapshots = r.stats;
  r.history.predict_at = 300;
  return r;
}

bool anyContains(const std::vector<std::string>& v, const std::string& what) {
  for (const auto& s : v) {
    if (s.find(what) != std::string::npos) return true;
  }
  return false;
}
}  // namespace

TEST(MixingVerdict, WellMixedBedMayBeExtrapolated) {
  const SyntheticRun r = trackedRun(3, 0.0);
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok) << fit.problem;
  const auto v = judgeMixing(fit, r.stats.back(), r.last);
  EXPECT_TRUE(v.well_mixed) << v.summary();
  EXPECT_TRUE(v.reasons.empty());
  EXPECT_DOUBLE_EQ(v.uncoated_share, 0.0);
  EXPECT_TRUE(v.normality.valid);
}

TEST(MixingVerdict, TwentyPercentNeverCoatedIsRefusedWithReasons) {
  const SyntheticRun r = trackedRun(5, 0.20);
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok) << fit.problem;
  // The mean still grows linearly (the coated 80 % take all the coating); the variance does not.
  EXPECT_NEAR(fit.a1, kA1, 0.02 * kA1);
  const auto v = judgeMixing(fit, r.stats.back(), r.last);
  EXPECT_FALSE(v.well_mixed);
  EXPECT_NEAR(v.uncoated_share, 0.20, 1e-12);
  EXPECT_TRUE(anyContains(v.reasons, "20.0 % of the parcels were never coated")) << v.summary();
  EXPECT_TRUE(anyContains(v.reasons, "variance of the coating mass is not linear")) << v.summary();
  EXPECT_TRUE(anyContains(v.reasons, "far from normal")) << v.summary();
  EXPECT_NE(v.summary().find("extrapolation refused"), std::string::npos);
}

TEST(MixingVerdict, SkewedDistributionAloneIsRefused) {
  // skewness 2: the normal reconstruction of Fig. 12 would be wrong.
  const SyntheticRun r = skewedRun();
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok);
  const auto v = judgeMixing(fit, r.stats.back(), r.last);
  EXPECT_FALSE(v.well_mixed);
  ASSERT_EQ(v.reasons.size(), 1u) << v.summary();
  EXPECT_TRUE(anyContains(v.reasons, "far from normal"));
  EXPECT_NEAR(v.normality.skewness, 2.0, 0.3);
  // Its skewness stays at 2 instead of fading: refused with its history too.
  NormalityHistory h;
  h.snapshots = r.stats;
  h.predict_at = 300;
  const auto withHistory = judgeMixing(fit, r.stats.back(), r.last, MixingCriteria{}, h);
  EXPECT_FALSE(withHistory.well_mixed);
  EXPECT_NEAR(withHistory.trend.skewness_decay, 0.0, 0.1);
  EXPECT_TRUE(anyContains(withHistory.reasons, "slower than")) << withHistory.summary();
}

TEST(MixingVerdict, NoFitIsRefused) {
  CoatingStatistics s;
  s.time = 1;
  s.count = 30;
  const auto fit = fitGrowth({s}, 0, 1);
  const auto v = judgeMixing(fit, s, std::vector<double>(30, 0.0));
  EXPECT_FALSE(v.well_mixed);
  EXPECT_TRUE(anyContains(v.reasons, "no fit"));
}

TEST(MixingVerdict, RelaxedCriteriaAllowAndAreNamed) {
  // The skewed run above, judged with the skewness/kurtosis/normality checks opened up: allowed,
  // and the verdict names every criterion that differs from its default.
  const SyntheticRun r = skewedRun();
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok);
  MixingCriteria c;
  c.max_abs_skewness = 3;
  c.max_abs_excess_kurtosis = 10;
  c.normality_alpha = 0;
  const auto v = judgeMixing(fit, r.stats.back(), r.last, c);
  EXPECT_TRUE(v.well_mixed) << v.summary();
  ASSERT_EQ(v.relaxed.size(), 3u);
  EXPECT_TRUE(anyContains(v.relaxed, "max_abs_skewness 3 (default 0.5)"));
  EXPECT_NE(v.summary().find("non-default criteria"), std::string::npos) << v.summary();
  // Defaults name nothing.
  EXPECT_TRUE(judgeMixing(fit, r.stats.back(), r.last).relaxed.empty());
}

TEST(MixingVerdict, ASkewedBedWhoseSkewnessFadesAsAWellMixedBedsIsExtrapolated) {
  // Compound Poisson passes at 0.45 per second: at 20 s the skewness is 3 / sqrt(2 * 0.45 * 20)
  // = 0.707 (over the 0.5 limit) and the excess kurtosis 6 / 9 = 0.67; a well-mixed bed's
  // skewness falls as t^-1/2, to 0.707 * sqrt(20 / 300) = 0.183 at the first reconstructed time.
  const PassRun r = passRun(11, 0.45);
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok) << fit.problem;
  EXPECT_NEAR(r.stats.back().skewness, 3.0 / std::sqrt(2 * 0.45 * 20), 0.08);

  // Judged on the last snapshot alone it is refused, as before.
  const auto alone = judgeMixing(fit, r.stats.back(), r.last);
  EXPECT_FALSE(alone.well_mixed);
  EXPECT_TRUE(alone.not_normal);

  const auto v = judgeMixing(fit, r.stats.back(), r.last, MixingCriteria{}, r.history);
  EXPECT_TRUE(v.well_mixed) << v.summary();
  EXPECT_TRUE(v.fading_non_normal);
  EXPECT_FALSE(v.not_normal);
  EXPECT_TRUE(v.relaxed.empty());
  ASSERT_TRUE(v.trend.measured);
  EXPECT_NEAR(v.trend.from, 5.0, 1e-12);
  EXPECT_NEAR(v.trend.to, 20.0, 1e-12);
  EXPECT_EQ(v.trend.snapshots, 31u);
  // 0.41-0.55 over eight draws of an independent script (numpy) with 4,000 parcels.
  EXPECT_NEAR(v.trend.skewness_decay, 0.5, 0.1);
  EXPECT_NEAR(v.trend.projected_skewness, 3.0 / std::sqrt(2 * 0.45 * 300), 0.03);
  EXPECT_DOUBLE_EQ(v.trend.at, 300.0);
  EXPECT_TRUE(anyContains(v.warnings, "fades as in a well-mixed bed")) << v.summary();
}

TEST(MixingVerdict, ASkewnessThatStaysIsRefusedWithItsRate) {
  // 20 % of the parcels pass 15 times less often (a dead zone): almost every parcel is coated by
  // 20 s (e^-4 of the slow ones at 0.2 passes per second: about 0.4 % of all never), but the slow
  // group falls behind linearly in time while the spread grows as sqrt(t), so the skewness does
  // not fade.
  const PassRun r = passRun(12, 3.0, 0.2, 0.2);
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  ASSERT_TRUE(fit.ok) << fit.problem;
  const auto v = judgeMixing(fit, r.stats.back(), r.last, MixingCriteria{}, r.history);
  EXPECT_FALSE(v.well_mixed) << v.summary();
  EXPECT_TRUE(v.not_normal);
  EXPECT_FALSE(v.fading_non_normal);
  EXPECT_FALSE(v.too_many_uncoated) << v.summary();
  ASSERT_TRUE(v.trend.measured);
  // About -2 (the slow group's lag grows as t, the spread as sqrt(t)): the skewness grows.
  EXPECT_LT(v.trend.skewness_decay, 0.0);
  EXPECT_TRUE(anyContains(v.reasons, "slower than t^-0.25")) << v.summary();
}

TEST(MixingVerdict, APastPredictionTimeGivesNoProjection) {
  // The same fading bed, but asked for a distribution before the run's end: nothing to project,
  // the last snapshot decides as without a history.
  PassRun r = passRun(11, 0.45);
  r.history.predict_at = 10;
  const auto fit = fitGrowth(r.stats, 0.0, 20.0);
  const auto v = judgeMixing(fit, r.stats.back(), r.last, MixingCriteria{}, r.history);
  EXPECT_FALSE(v.well_mixed);
  EXPECT_TRUE(v.not_normal);
  EXPECT_TRUE(std::isnan(v.trend.at));
}
