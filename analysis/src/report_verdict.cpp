// The verdict in plain words: one or two sentences a process engineer reads first (is the bed
// well mixed, can its coating be extrapolated to a batch of 20-60 min, with what CV), built from
// the verdict's criteria and the numbers behind them.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cosim/analysis/display_units.h"
#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
constexpr const char* kNbsp = "\u00a0";

}  // namespace

std::vector<double> batchTimes(const ReportOptions& o) {
  std::vector<double> t;
  if (!o.predict_times.empty())
    t.push_back(*std::max_element(o.predict_times.begin(), o.predict_times.end()));
  if (t.empty() || o.predict_until > t.back()) t.push_back(o.predict_until);
  return t;
}

std::string batchRange(const ReportOptions& o) {
  const auto t = batchTimes(o);
  if (t.size() == 1) return textDuration(t.front());
  return textNumber(t.front() / 60.0, 3) + "\u2013" + textNumber(t.back() / 60.0, 3) + kNbsp +
         "min";
}

std::string shortVerdict(const MixingVerdict& v) {
  if (!v.well_mixed) return "poorly mixed";
  return v.relaxed.empty() ? "well mixed" : "well mixed under relaxed criteria";
}

VerdictText verdictText(const RunAnalysis& a, const ReportOptions& o) {
  const auto& v = a.verdict;
  const auto& c = a.conditions;
  // The snapshot the verdict judged: its time and numbers.
  const CoatingStatistics* judged = &a.snapshots.back();
  for (const auto& s : a.snapshots) {
    if (s.time == v.last_time) judged = &s;
  }
  const double coated = judged->time - std::max(a.snapshots.front().time, o.coating_start);
  VerdictText t;
  std::string& s = t.body;
  if (!v.well_mixed) {
    t.head = "Poorly mixed";
    s = "after " + textDuration(coated) + " of coating";
    std::vector<std::string> what;
    if (v.too_many_uncoated)
      what.push_back(textPercent(judged->uncoated_share) +
                     " of the parcels have no coating at all");
    if (v.not_normal) what.push_back("the coating is far from normally distributed");
    if (v.mean_not_linear || v.variance_not_linear)
      what.push_back("the coating does not yet grow steadily with time");
    if (v.no_fit) what.push_back("there are too few snapshots to tell how the coating grows");
    for (std::size_t i = 0; i < what.size(); ++i) {
      s += (i == 0 ? " " : (i + 1 == what.size() ? " and " : ", ")) + what[i];
    }
    s += "; the CV is " + textNumber(judged->cv, 3) + ". The coating cannot be extrapolated to a " +
         batchRange(o) + " batch.";
    if (a.zone_passes && std::isfinite(a.zone_passes->stats.cycle_time_from_rate)) {
      const auto& z = a.zone_passes->stats;
      s += " A parcel enters the coating zone only every " + textDuration(z.cycle_time_from_rate) +
           " on average (" + textPercent(z.never_entered_share) +
           " never did in this run): a run several times that long, or a flow that turns the bed "
           "over "
           "faster, is needed before the batch can be judged.";
    }
    return t;
  }
  if (!v.relaxed.empty()) {
    t.head = "Well mixed only under relaxed criteria";
    for (std::size_t i = 0; i < v.relaxed.size(); ++i) s += (i ? ", " : "") + v.relaxed[i];
    s += "; the extrapolation is at your own risk. After ";
  } else {
    t.head = "Well mixed";
    s = "after ";
  }
  s += textDuration(coated) + " of coating " + textPercent(1.0 - judged->uncoated_share) +
       " of the parcels are coated and the coating grows as in a well-mixed bed; the CV is " +
       textNumber(judged->cv, 3) + ".";
  if (v.fading_non_normal && std::isfinite(v.trend.at)) {
    s += " The coating is not yet normally distributed (skewness " +
         textNumber(judged->skewness, 3) + ", excess kurtosis " +
         textNumber(judged->excess_kurtosis, 3) +
         ") but evens out as a well-mixed bed's does, to " +
         textNumber(v.trend.projected_skewness, 3) + " and " +
         textNumber(v.trend.projected_excess_kurtosis, 3) + " at " + textDuration(v.trend.at) + ".";
  }
  if (a.fit.ok) {
    const auto times = batchTimes(o);
    s += " Extrapolated to a " + batchRange(o) + " batch the CV would be ";
    for (std::size_t i = 0; i < times.size(); ++i) {
      const auto d = predictDistribution(a.fit, times[i], o.band);
      s += (i ? " and " : "") + textNumber(d.cv, 3) + " at " + textDuration(times[i]);
    }
    const std::string band = fmt::format("{:.0f}", 100 * o.band) + kNbsp + "%";
    s += " (each \u00b1" + band + " for a " + band + " error in a2); at " +
         textDuration(times.front()) + " a real grain would carry ";
    const auto d = predictDistribution(a.fit, times.front(), o.band);
    s += textQuantity(c.grain.perGrain(d.mean), a.mass_unit);
    const double h = c.grain.thickness(d.mean);
    if (std::isfinite(h)) s += ", a layer of " + textQuantity(h, a.thickness_unit);
    s += ".";
  }
  return t;
}

std::string plainVerdict(const RunAnalysis& a, const ReportOptions& o) {
  const auto t = verdictText(a, o);
  return t.head + ": " + t.body;
}

}  // namespace cosim::analysis
