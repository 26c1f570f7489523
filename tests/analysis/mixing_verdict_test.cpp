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
