// Mixing verdict: may the Eqs. 9-10 fit be extrapolated to long coating times? It refuses, with
// each reason in words, when mixing is poor (paper section 2.3 and 4.5, docs/physics.md section 5):
//  1. never-coated share at the last snapshot above max_uncoated_share (the paper's 1 L/min
//     case has 15 % uncoated after 20 s);
//  2. large misfit: relative RMS residual of the mean or variance fit above its limit;
//  3. distribution far from normal at the last snapshot: the D'Agostino-Pearson test rejects
//     (p < normality_alpha) AND the departure is material (|g1| > max_abs_skewness or
//     |b2 - 3| > max_abs_excess_kurtosis). With tens of thousands of parcels the test alone
//     rejects even tiny departures, hence the effect-size condition. Given the snapshots of the
//     fit window (NormalityHistory), a departure that fades as a well-mixed bed's does is a
//     warning instead: in a well-mixed bed (Mann's cycle-time picture: each parcel's coating a
//     sum of a growing number of independent passes) every cumulant of the coating grows linearly
//     in time, so the skewness falls as t^-1/2 and the excess kurtosis as t^-1. The departure is
//     taken as transient when, over the last three quarters of the coating time (the fit window's
//     snapshots with t_last / 4 <= t <= t_last), |g1| falls at least as
//     t^-min_skewness_decay (|g2| as t^-min_kurtosis_decay) and, projected with that rate (at
//     most the well-mixed one) to the first time the report reconstructs a distribution, it is
//     within the limits above;
//  4. no valid fit at all.
// Structured residuals (runs test p < runs_alpha) and an untestable normality give warnings.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/growth_fit.h"
#include "cosim/analysis/normality_test.h"
#include "cosim/analysis/runs_test.h"

namespace cosim::analysis {

struct MixingCriteria {
  double max_uncoated_share = 0.05;
  double max_mean_relative_rms = 0.10;
  double max_variance_relative_rms = 0.25;
  double normality_alpha = 1e-3;
  double max_abs_skewness = 0.5;
  double max_abs_excess_kurtosis = 1.0;
  double runs_alpha = 1e-3;
  // Slowest decay exponents b (|g1| ~ t^-b, |g2| ~ t^-b) for which a skewed distribution counts as
  // a well-mixed bed on its way to normal: half the well-mixed bed's 1/2 and 1 (a bed with a dead
  // zone: b <= 0; the sampling noise of b with 4,000 parcels: about +-0.05 for g1, +-0.2 for g2).
  double min_skewness_decay = 0.25;
  double min_kurtosis_decay = 0.5;
};

// Every criterion by its name (the names of `cosim report --mixing NAME=VALUE` and report.json).
struct MixingCriterion {
  const char* name;
  double MixingCriteria::*value;
};
inline constexpr MixingCriterion kMixingCriteria[] = {
    {"max_uncoated_share", &MixingCriteria::max_uncoated_share},
    {"max_mean_relative_rms", &MixingCriteria::max_mean_relative_rms},
    {"max_variance_relative_rms", &MixingCriteria::max_variance_relative_rms},
    {"normality_alpha", &MixingCriteria::normality_alpha},
    {"max_abs_skewness", &MixingCriteria::max_abs_skewness},
    {"max_abs_excess_kurtosis", &MixingCriteria::max_abs_excess_kurtosis},
    {"runs_alpha", &MixingCriteria::runs_alpha},
    {"min_skewness_decay", &MixingCriteria::min_skewness_decay},
    {"min_kurtosis_decay", &MixingCriteria::min_kurtosis_decay}};

// What the verdict needs to tell a fading departure from normality from a lasting one.
struct NormalityHistory {
  std::vector<CoatingStatistics> snapshots;  // the fit window's, in time order
  double coating_start = 0;                  // [s] origin of the coating time
  // [s] of coating: the first time at which a distribution is reconstructed (report --predict)
  double predict_at = std::numeric_limits<double>::quiet_NaN();
};

// How the departure from normality decays over the last three quarters of the coating time.
struct NormalityTrend {
  bool measured = false;    // at least 3 snapshots with a finite departure there
  double from = 0, to = 0;  // [s] coating time of the first and last snapshot used
  std::size_t snapshots = 0;
  double skewness_decay = std::numeric_limits<double>::quiet_NaN();  // b of |g1| ~ t^-b
  double kurtosis_decay = std::numeric_limits<double>::quiet_NaN();  // b of |g2| ~ t^-b
  double at = std::numeric_limits<double>::quiet_NaN();  // [s] coating time projected to
  double projected_skewness = std::numeric_limits<double>::quiet_NaN();         // |g1| there
  double projected_excess_kurtosis = std::numeric_limits<double>::quiet_NaN();  // |g2| there
};

struct MixingVerdict {
  bool well_mixed = false;            // true: extrapolation allowed
  std::vector<std::string> reasons;   // why refused (empty when well mixed)
  std::vector<std::string> warnings;  // worth knowing, not refusing
  std::vector<std::string> relaxed;  // criteria set away from their defaults ("name v (default d)")
  // Which refusal criteria failed (each has its sentence in reasons).
  bool too_many_uncoated = false;    // never-coated share above the limit
  bool no_fit = false;               // no fit of Eqs. 9-10
  bool mean_not_linear = false;      // misfit of the mean
  bool variance_not_linear = false;  // misfit of the variance
  bool not_normal = false;           // far from normal
  bool fading_non_normal = false;    // far from normal now, within the limits by trend.at
  NormalityTrend trend;              // measured when the last snapshot is far from normal
  RunsTest mean_runs, variance_runs;
  NormalityTest normality;    // on the last snapshot
  double uncoated_share = 0;  // at the last snapshot
  double last_time = 0;
  std::string summary() const;  // one line: "well mixed" or "poorly mixed: ..."
};

// last: statistics of the last snapshot; last_values: its coating masses (for the normality test).
// Without a history a departure from normality at the last snapshot is always a refusal.
MixingVerdict judgeMixing(const GrowthFit& fit, const CoatingStatistics& last,
                          const std::vector<double>& last_values,
                          const MixingCriteria& criteria = {});
MixingVerdict judgeMixing(const GrowthFit& fit, const CoatingStatistics& last,
                          const std::vector<double>& last_values, const MixingCriteria& criteria,
                          const NormalityHistory& history);

// The decay of the departure from normality over the snapshots whose coating time lies in
// [t_last / 4, t_last], and its projection to history.predict_at (NaN projection when predict_at
// is not after t_last).
NormalityTrend normalityTrend(const NormalityHistory& history, const CoatingStatistics& last);

}  // namespace cosim::analysis
