// Mixing verdict: may the Eqs. 9-10 fit be extrapolated to long coating times? It refuses, with
// each reason in words, when mixing is poor (paper section 2.3 and 4.5, docs/physics.md section 5):
//  1. never-coated share at the last snapshot above max_uncoated_share (the paper's 1 L/min
//     case has 15 % uncoated after 20 s);
//  2. large misfit: relative RMS residual of the mean or variance fit above its limit;
//  3. distribution far from normal at the last snapshot: the D'Agostino-Pearson test rejects
//     (p < normality_alpha) AND the departure is material (|g1| > max_abs_skewness or
//     |b2 - 3| > max_abs_excess_kurtosis). With tens of thousands of parcels the test alone
//     rejects even tiny departures, hence the effect-size condition;
//  4. no valid fit at all.
// Structured residuals (runs test p < runs_alpha) and an untestable normality give warnings.
#pragma once

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
    {"runs_alpha", &MixingCriteria::runs_alpha}};

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
  RunsTest mean_runs, variance_runs;
  NormalityTest normality;    // on the last snapshot
  double uncoated_share = 0;  // at the last snapshot
  double last_time = 0;
  std::string summary() const;  // one line: "well mixed" or "poorly mixed: ..."
};

// last: statistics of the last snapshot; last_values: its coating masses (for the normality test).
MixingVerdict judgeMixing(const GrowthFit& fit, const CoatingStatistics& last,
                          const std::vector<double>& last_values,
                          const MixingCriteria& criteria = {});

}  // namespace cosim::analysis
