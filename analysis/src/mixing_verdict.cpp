#include "cosim/analysis/mixing_verdict.h"

#include <fmt/format.h>

#include <cmath>

namespace cosim::analysis {

std::string MixingVerdict::summary() const {
  if (well_mixed && !relaxed.empty()) {
    std::string s = "well mixed under non-default criteria (";
    for (std::size_t i = 0; i < relaxed.size(); ++i) s += (i ? ", " : "") + relaxed[i];
    return s + "): extrapolation allowed at the user's risk";
  }
  if (well_mixed) return "well mixed: extrapolation allowed";
  std::string s = "poorly mixed, extrapolation refused: ";
  for (std::size_t i = 0; i < reasons.size(); ++i) s += (i ? "; " : "") + reasons[i];
  return s;
}

MixingVerdict judgeMixing(const GrowthFit& fit, const CoatingStatistics& last,
                          const std::vector<double>& last_values, const MixingCriteria& c) {
  MixingVerdict v;
  const MixingCriteria d;
  for (const auto& k : kMixingCriteria) {
    if (c.*k.value != d.*k.value) {
      v.relaxed.push_back(std::string(k.name) + " " + fmt::format("{:g}", c.*k.value) +
                          " (default " + fmt::format("{:g}", d.*k.value) + ")");
    }
  }
  v.last_time = last.time;
  v.uncoated_share = last.uncoated_share;
  if (last.count > 0 && last.uncoated_share > c.max_uncoated_share) {
    v.too_many_uncoated = true;
    v.reasons.push_back(
        fmt::format("{:.1f} %", 100 * last.uncoated_share) +
        " of the parcels were never coated by t = " + fmt::format("{:g}", last.time) +
        " s (limit " + fmt::format("{:.1f} %", 100 * c.max_uncoated_share) +
        "): some particles do not reach the coating zone");
  }
  if (!fit.ok) {
    v.no_fit = true;
    v.reasons.push_back("no fit of Eqs. 9-10: " + fit.problem);
  } else {
    if (fit.mean_relative_rms > c.max_mean_relative_rms) {
      v.mean_not_linear = true;
      v.reasons.push_back("the mean coating mass is not linear in time: RMS residual " +
                          fmt::format("{:.1f} %", 100 * fit.mean_relative_rms) +
                          " of the mean (limit " +
                          fmt::format("{:.0f} %", 100 * c.max_mean_relative_rms) + ")");
    }
    if (fit.variance_relative_rms > c.max_variance_relative_rms) {
      v.variance_not_linear = true;
      v.reasons.push_back("the variance of the coating mass is not linear in time: RMS residual " +
                          fmt::format("{:.1f} %", 100 * fit.variance_relative_rms) +
                          " of the mean variance (limit " +
                          fmt::format("{:.0f} %", 100 * c.max_variance_relative_rms) + ")");
    }
    v.mean_runs = runsTest(fit.mean_fit.residuals);
    v.variance_runs = runsTest(fit.variance_fit.residuals);
    if (v.mean_runs.valid && v.mean_runs.p_too_few < c.runs_alpha) {
      v.warnings.push_back("residuals of the mean fit are structured (" +
                           std::to_string(v.mean_runs.runs) + " sign runs, " +
                           fmt::format("{:.1f}", v.mean_runs.expected_runs) +
                           " expected, p = " + fmt::format("{:.2g}", v.mean_runs.p_too_few) + ")");
    }
    if (v.variance_runs.valid && v.variance_runs.p_too_few < c.runs_alpha) {
      v.warnings.push_back(
          "residuals of the variance fit are structured (" + std::to_string(v.variance_runs.runs) +
          " sign runs, " + fmt::format("{:.1f}", v.variance_runs.expected_runs) +
          " expected, p = " + fmt::format("{:.2g}", v.variance_runs.p_too_few) + ")");
    }
  }
  v.normality = dagostinoPearson(last_values);
  if (!v.normality.valid) {
    v.warnings.push_back(v.normality.problem);
  } else if (v.normality.p_value < c.normality_alpha) {
    const double excess = v.normality.kurtosis - 3.0;
    if (std::abs(v.normality.skewness) > c.max_abs_skewness ||
        std::abs(excess) > c.max_abs_excess_kurtosis) {
      v.not_normal = true;
      v.reasons.push_back(
          "the coating distribution at t = " + fmt::format("{:g}", last.time) +
          " s is far from normal (skewness " + fmt::format("{:.2f}", v.normality.skewness) +
          ", excess kurtosis " + fmt::format("{:.2f}", excess) +
          ", D'Agostino-Pearson p = " + fmt::format("{:.2g}", v.normality.p_value) + ")");
    } else {
      v.warnings.push_back(
          "the normality test rejects at p = " + fmt::format("{:.2g}", v.normality.p_value) +
          " but the departure is small (skewness " + fmt::format("{:.2f}", v.normality.skewness) +
          ", excess kurtosis " + fmt::format("{:.2f}", excess) + ")");
    }
  }
  v.well_mixed = v.reasons.empty();
  return v;
}

}  // namespace cosim::analysis
