#include "cosim/analysis/zone_pass_statistics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace cosim::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

Spread spreadOf(const std::vector<double>& values, bool sample) {
  Spread s;
  s.n = values.size();
  if (values.empty()) return s;
  std::vector<double> v = values;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  const double n = static_cast<double>(v.size());
  s.mean = sum / n;
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  const double dof = sample ? n - 1 : n;
  s.sd = dof > 0 ? std::sqrt(ss / dof) : kNaN;
  s.min = v.front();
  s.max = v.back();
  s.p10 = quantileSorted(v, 0.10);
  s.p25 = quantileSorted(v, 0.25);
  s.p50 = quantileSorted(v, 0.50);
  s.p75 = quantileSorted(v, 0.75);
  s.p90 = quantileSorted(v, 0.90);
  s.histogram = histogram(v);
  return s;
}

MannPrediction mannPrediction(double w0, double mu_t, double sigma_t, double sigma_w, double t) {
  MannPrediction p;
  p.t = t;
  p.passes_mean = t / mu_t;
  p.mean = w0 * t / mu_t;
  p.sd = w0 * sigma_t * std::sqrt(t / (mu_t * mu_t * mu_t));
  p.cv = sigma_t / std::sqrt(mu_t * t);
  const double rel_t = sigma_t / mu_t;
  const double rel_w = sigma_w / w0;
  p.cv_with_pass_spread = std::sqrt((rel_t * rel_t + rel_w * rel_w) * mu_t / t);
  return p;
}

ZonePassStatistics zonePassStatistics(const std::vector<ZonePass>& passes,
                                      const std::vector<std::int64_t>& parcel_ids, double start,
                                      double end) {
  ZonePassStatistics s;
  s.start = start;
  s.end = end;
  s.parcels = parcel_ids.size();
  s.ids = parcel_ids;
  s.parcel_passes.assign(s.parcels, 0);
  s.parcel_time_in_zone.assign(s.parcels, 0.0);
  s.parcel_coating.assign(s.parcels, 0.0);
  std::unordered_map<std::int64_t, std::size_t> column;
  for (std::size_t i = 0; i < parcel_ids.size(); ++i) column.emplace(parcel_ids[i], i);

  // Entries of each parcel in time order, for the cycles.
  std::map<std::int64_t, std::vector<double>> entries;
  std::vector<double> durations, coatings, cycles;
  double time_in_zone = 0;
  for (const auto& p : passes) {
    ++s.passes;
    s.coating_in_passes += p.coating;
    time_in_zone += p.duration();
    if (!p.at_start) {
      ++s.entries;
      entries[p.parcel_id].push_back(p.entry_time);
    }
    if (p.complete()) {
      ++s.complete_passes;
      durations.push_back(p.duration());
      coatings.push_back(p.coating);
    }
    if (auto it = column.find(p.parcel_id); it != column.end()) {
      ++s.parcel_passes[it->second];
      s.parcel_time_in_zone[it->second] += p.duration();
      s.parcel_coating[it->second] += p.coating;
    }
  }
  for (auto& [id, e] : entries) {
    std::sort(e.begin(), e.end());
    for (std::size_t k = 1; k < e.size(); ++k) cycles.push_back(e[k] - e[k - 1]);
  }
  std::vector<double> counts(s.parcels);
  for (std::size_t i = 0; i < s.parcels; ++i) {
    counts[i] = static_cast<double>(s.parcel_passes[i]);
    if (s.parcel_passes[i] == 0) ++s.never_entered;
    const auto it = entries.find(parcel_ids[i]);
    if (it == entries.end() || it->second.size() < 2) ++s.at_most_one_entry;
  }
  const double duration = end - start;
  if (s.parcels > 0) {
    s.never_entered_share = static_cast<double>(s.never_entered) / static_cast<double>(s.parcels);
    s.passes_per_parcel = spreadOf(counts, false);
    // One bin per whole number of passes (up to 100 bins).
    const auto span = static_cast<std::size_t>(s.passes_per_parcel.max - s.passes_per_parcel.min);
    if (span > 0 && span < 100) s.passes_per_parcel.histogram = histogram(counts, span + 1);
    s.passes_cv =
        s.passes_per_parcel.mean > 0 ? s.passes_per_parcel.sd / s.passes_per_parcel.mean : kNaN;
    s.time_in_zone_per_parcel = spreadOf(s.parcel_time_in_zone, false);
    if (duration > 0)
      s.time_in_zone_share = time_in_zone / (static_cast<double>(s.parcels) * duration);
  }
  if (time_in_zone > 0) s.uptake_rate_in_zone = s.coating_in_passes / time_in_zone;
  s.pass_duration = spreadOf(durations, true);
  s.cycle_time = spreadOf(cycles, true);
  s.coating_per_pass = spreadOf(coatings, true);
  if (s.entries > 0 && duration > 0)
    s.cycle_time_from_rate =
        static_cast<double>(s.parcels) * duration / static_cast<double>(s.entries);
  if (s.passes > 0) s.w0 = s.coating_in_passes / static_cast<double>(s.passes);

  if (cycles.size() < 2) {
    s.prediction_problem =
        "fewer than 2 cycles (a parcel entering the zone twice) in the run: no "
        "cycle-time statistics; run longer";
  } else if (!(s.w0 > 0)) {
    s.prediction_problem = "no coating in the passes: no coating per pass";
  } else if (!(s.cycle_time.mean > 0)) {
    s.prediction_problem = "mean cycle time is zero";
  } else {
    s.prediction_ok = true;
  }
  return s;
}

MannPrediction predictFromPasses(const ZonePassStatistics& s, double t) {
  if (!s.prediction_ok) {
    MannPrediction p;
    p.t = t;
    p.mean = p.sd = p.cv = p.passes_mean = p.cv_with_pass_spread = kNaN;
    return p;
  }
  const double sigma_w = s.coating_per_pass.n >= 2 ? s.coating_per_pass.sd : 0.0;
  return mannPrediction(s.w0, s.cycle_time.mean, s.cycle_time.sd, sigma_w, t);
}

}  // namespace cosim::analysis
