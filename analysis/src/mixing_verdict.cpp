#include "cosim/analysis/mixing_verdict.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cosim::analysis {

namespace {
// b of |y| ~ x^-b by least squares of ln|y| on ln x; NaN with fewer than 3 usable points.
double decayExponent(const std::vector<double>& x, const std::vector<double>& y) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !std::isfinite(y[i]) || y[i] == 0) continue;
    const double lx = std::log(x[i]), ly = std::log(std::abs(y[i]));
    n += 1;
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  if (n < 3 || !(d > 1e-12 * n * n)) return std::numeric_limits<double>::quiet_NaN();
  return -(n * sxy - sx * sy) / d;
}
}  // namespace

NormalityTrend normalityTrend(const NormalityHistory& h, const CoatingStatistics& last) {
  NormalityTrend tr;
  const double tauLast = last.time - h.coating_start;
  if (!(tauLast > 0)) return tr;
  std::vector<double> tau, g1, g2;
  for (const auto& s : h.snapshots) {
    const double t = s.time - h.coating_start;
    if (t < 0.25 * tauLast || t > tauLast * (1 + 1e-12) || s.count == 0) continue;
    tau.push_back(t);
    g1.push_back(s.skewness);
    g2.push_back(s.excess_kurtosis);
  }
  tr.snapshots = tau.size();
  if (tau.empty()) return tr;
  tr.from = tau.front();
  tr.to = tau.back();
  tr.skewness_decay = decayExponent(tau, g1);
  tr.kurtosis_decay = decayExponent(tau, g2);
  tr.measured = std::isfinite(tr.skewness_decay) || std::isfinite(tr.kurtosis_decay);
  if (tr.measured && h.predict_at > tauLast) {
    tr.at = h.predict_at;
    // Projected at the measured rate, at most the well-mixed one (1/2, 1): a faster fall early on
    // is not extrapolated.
    const double r = tauLast / h.predict_at;
    if (std::isfinite(tr.skewness_decay))
      tr.projected_skewness =
          std::abs(last.skewness) * std::pow(r, std::min(tr.skewness_decay, 0.5));
    if (std::isfinite(tr.kurtosis_decay))
      tr.projected_excess_kurtosis =
          std::abs(last.excess_kurtosis) * std::pow(r, std::min(tr.kurtosis_decay, 1.0));
  }
  return tr;
}

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
  return judgeMixing(fit, last, last_values, c, NormalityHistory{});
}

namespace {
// Eqs. 9-10's fit: are the mean and the variance linear in time, are their residuals random.
void judgeFit(const GrowthFit& fit, const MixingCriteria& c, MixingVerdict& v) {
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
}

// The coating distribution at the last snapshot: normal, or departing in a way that fades as in
// a well-mixed bed, or lasting.
void judgeNormality(const CoatingStatistics& last, const std::vector<double>& last_values,
                    const MixingCriteria& c, const NormalityHistory& history, MixingVerdict& v) {
  v.normality = dagostinoPearson(last_values);
  if (!v.normality.valid) {
    v.warnings.push_back(v.normality.problem);
  } else if (v.normality.p_value < c.normality_alpha) {
    const double excess = v.normality.kurtosis - 3.0;
    const bool skewed = std::abs(v.normality.skewness) > c.max_abs_skewness;
    const bool peaked = std::abs(excess) > c.max_abs_excess_kurtosis;
    if (skewed || peaked) {
      const auto where =
          "the coating distribution at t = " + fmt::format("{:g}", last.time) +
          " s is far from normal (skewness " + fmt::format("{:.2f}", v.normality.skewness) +
          ", excess kurtosis " + fmt::format("{:.2f}", excess) +
          ", D'Agostino-Pearson p = " + fmt::format("{:.2g}", v.normality.p_value) + ")";
      v.trend = normalityTrend(history, last);
      const auto& tr = v.trend;
      // One moment of the departure: lasting (a reason, "" for the bare one) or fading.
      std::vector<std::string> lasting, fading;
      const auto judge = [&](const char* what, double b, double min_decay, double wanted,
                             double projected, double limit) {
        const auto rate = std::string(what) + " falls as t^-" + fmt::format("{:.2f}", b) +
                          " over " + fmt::format("{:g}", tr.from) + "-" +
                          fmt::format("{:g}", tr.to) + " s of coating (a well-mixed bed's as t^-" +
                          fmt::format("{:g}", wanted) + ")";
        const auto there =
            fmt::format("{:.2f}", projected) + " at " + fmt::format("{:g}", tr.at) + " s";
        if (!std::isfinite(b)) {
          lasting.push_back("");
        } else if (b < min_decay) {
          lasting.push_back(rate + ", slower than t^-" + fmt::format("{:g}", min_decay));
        } else if (!std::isfinite(tr.at)) {
          lasting.push_back("");  // the run is already past the first reconstructed time
        } else if (!(projected <= limit)) {
          lasting.push_back(rate + " but would still be " + there);
        } else {
          fading.push_back(rate + ", to " + there);
        }
      };
      if (skewed)
        judge("its skewness", tr.skewness_decay, c.min_skewness_decay, 0.5, tr.projected_skewness,
              c.max_abs_skewness);
      if (peaked)
        judge("its excess kurtosis", tr.kurtosis_decay, c.min_kurtosis_decay, 1.0,
              tr.projected_excess_kurtosis, c.max_abs_excess_kurtosis);
      const auto join = [](const std::vector<std::string>& parts) {
        std::string r;
        for (const auto& p : parts) {
          if (p.empty()) continue;
          r += (r.empty() ? "" : "; ") + p;
        }
        return r;
      };
      if (lasting.empty()) {
        v.fading_non_normal = true;
        v.warnings.push_back(where +
                             ", but the departure fades as in a well-mixed bed: " + join(fading) +
                             ", within the limits where the report reconstructs the distribution");
      } else {
        v.not_normal = true;
        const auto why = join(lasting);
        v.reasons.push_back(why.empty() ? where : where + ": " + why);
      }
    } else {
      v.warnings.push_back(
          "the normality test rejects at p = " + fmt::format("{:.2g}", v.normality.p_value) +
          " but the departure is small (skewness " + fmt::format("{:.2f}", v.normality.skewness) +
          ", excess kurtosis " + fmt::format("{:.2f}", excess) + ")");
    }
  }
}
}  // namespace

MixingVerdict judgeMixing(const GrowthFit& fit, const CoatingStatistics& last,
                          const std::vector<double>& last_values, const MixingCriteria& c,
                          const NormalityHistory& history) {
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
  judgeFit(fit, c, v);
  judgeNormality(last, last_values, c, history, v);
  v.well_mixed = v.reasons.empty();
  return v;
}

}  // namespace cosim::analysis
