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

std::string number(double v, int digits = 3) {
  return std::isfinite(v) ? textNumber(v, digits) : "?";
}
std::string duration(double s) {
  if (!std::isfinite(s)) return "?";
  if (std::abs(s) < 1.0) return number(1e3 * s) + kNbsp + "ms";
  if (std::abs(s) > 120.0) return number(s / 60.0) + kNbsp + "min";
  return number(s) + kNbsp + "s";
}
std::string percent(double share) { return number(100.0 * share) + kNbsp + "%"; }
std::string quantity(double si, const DisplayUnit& u) {
  return std::isfinite(si) ? number(u.of(si)) + kNbsp + u.name : "?";
}
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
  if (t.size() == 1) return duration(t.front());
  return number(t.front() / 60.0) + "\u2013" + number(t.back() / 60.0) + kNbsp + "min";
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
    s = "after " + duration(coated) + " of coating";
    std::vector<std::string> what;
    if (v.too_many_uncoated)
      what.push_back(percent(judged->uncoated_share) + " of the parcels have no coating at all");
    if (v.not_normal) what.push_back("the coating is far from normally distributed");
    if (v.mean_not_linear || v.variance_not_linear)
      what.push_back("the coating does not yet grow steadily with time");
    if (v.no_fit) what.push_back("there are too few snapshots to tell how the coating grows");
    for (std::size_t i = 0; i < what.size(); ++i) {
      s += (i == 0 ? " " : (i + 1 == what.size() ? " and " : ", ")) + what[i];
    }
    s += "; the CV is " + number(judged->cv) + ". The coating cannot be extrapolated to a " +
         batchRange(o) + " batch.";
    if (a.zone_passes && std::isfinite(a.zone_passes->stats.cycle_time_from_rate)) {
      const auto& z = a.zone_passes->stats;
      s += " A parcel enters the coating zone only every " + duration(z.cycle_time_from_rate) +
           " on average (" + percent(z.never_entered_share) +
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
  s += duration(coated) + " of coating " + percent(1.0 - judged->uncoated_share) +
       " of the parcels are coated and the coating grows as in a well-mixed bed; the CV is " +
       number(judged->cv) + ".";
  if (v.fading_non_normal && std::isfinite(v.trend.at)) {
    s += " The coating is not yet normally distributed (skewness " + number(judged->skewness) +
         ", excess kurtosis " + number(judged->excess_kurtosis) +
         ") but evens out as a well-mixed bed's does, to " + number(v.trend.projected_skewness) +
         " and " + number(v.trend.projected_excess_kurtosis) + " at " + duration(v.trend.at) + ".";
  }
  if (a.fit.ok) {
    const auto times = batchTimes(o);
    s += " Extrapolated to a " + batchRange(o) + " batch the CV would be ";
    for (std::size_t i = 0; i < times.size(); ++i) {
      const auto d = predictDistribution(a.fit, times[i], o.band);
      s += (i ? " and " : "") + number(d.cv) + " at " + duration(times[i]);
    }
    const std::string band = fmt::format("{:.0f}", 100 * o.band) + kNbsp + "%";
    s += " (each \u00b1" + band + " for a " + band + " error in a2); at " +
         duration(times.front()) + " a real grain would carry ";
    const auto d = predictDistribution(a.fit, times.front(), o.band);
    s += quantity(c.grain.perGrain(d.mean), a.mass_unit);
    const double h = c.grain.thickness(d.mean);
    if (std::isfinite(h)) s += ", a layer of " + quantity(h, a.thickness_unit);
    s += ".";
  }
  return t;
}

std::string plainVerdict(const RunAnalysis& a, const ReportOptions& o) {
  const auto t = verdictText(a, o);
  return t.head + ": " + t.body;
}

}  // namespace cosim::analysis
