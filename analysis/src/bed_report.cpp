#include "cosim/analysis/bed_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "report_internal.h"

namespace cosim::analysis {

WindowStatistics statisticsOf(const std::vector<double>& values) {
  WindowStatistics s;
  double sum = 0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    if (s.n == 0) s.min = s.max = v;
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    sum += v;
    ++s.n;
  }
  if (s.n == 0) return s;
  s.mean = sum / static_cast<double>(s.n);
  double sq = 0;
  for (const double v : values)
    if (std::isfinite(v)) sq += (v - s.mean) * (v - s.mean);
  s.sd = s.n > 1 ? std::sqrt(sq / static_cast<double>(s.n - 1)) : 0.0;
  return s;
}

namespace {

// The q-quantile (0..1) of `v`, linear between order statistics; v is reordered.
double quantile(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

bool inWindow(double t, double from, double to) { return t >= from - 1e-9 && t <= to + 1e-9; }

// The series' rows in the window: pressure drop and parcel count.
void readSeries(const TimeSeries& ts, const std::filesystem::path& file, BedAnalysis& a) {
  const auto& time = ts.at("time");
  auto column = [&](const char* name, WindowStatistics& out) {
    if (!ts.has(name)) {
      a.notes.push_back(fmt::format("{} has no column {}", file.string(), name));
      return;
    }
    std::vector<double> in;
    const auto& v = ts.at(name);
    for (std::size_t r = 0; r < ts.rows(); ++r)
      if (inWindow(time[r], a.from, a.to)) in.push_back(v[r]);
    out = statisticsOf(in);
  };
  column("pressure_drop", a.pressure_drop);
  column("particle_count", a.particle_count);
}

// The snapshots in the window: the bed's height and the parcels' speed in each.
void readParticles(const ParticleFile& file, BedAnalysis& a) {
  if (!file.hasField(field::position)) {
    a.notes.push_back(file.path().string() + " holds no positions: no bed height");
    return;
  }
  std::vector<double> median, p90, speed;
  const bool velocity = file.hasField(field::velocity);
  if (!velocity) a.notes.push_back(file.path().string() + " holds no velocity: no parcel speeds");
  const auto& snaps = file.snapshots();
  for (std::size_t k = 0; k < snaps.size(); ++k) {
    if (!inWindow(snaps[k].time, a.from, a.to)) continue;
    const auto x = file.read(k, field::position);
    if (x.size() < 3) continue;
    std::vector<double> z;
    z.reserve(x.size() / 3);
    for (std::size_t i = 2; i < x.size(); i += 3) z.push_back(x[i]);
    median.push_back(quantile(z, 0.5));
    p90.push_back(quantile(z, 0.9));
    if (velocity) {
      const auto u = file.read(k, field::velocity);
      std::vector<double> s;
      s.reserve(u.size() / 3);
      for (std::size_t i = 0; i + 2 < u.size(); i += 3)
        s.push_back(std::hypot(u[i], u[i + 1], u[i + 2]));
      if (!s.empty()) speed.push_back(quantile(s, 0.5));
    }
    ++a.snapshots;
  }
  a.height_median = statisticsOf(median);
  a.height_p90 = statisticsOf(p90);
  a.speed_median = statisticsOf(speed);
}

// The record's first and last time: the series' rows, else the snapshots.
std::pair<double, double> recordSpan(const std::optional<TimeSeries>& series,
                                     const std::optional<ParticleFile>& particles) {
  double first = std::numeric_limits<double>::infinity(), last = -first;
  if (series && series->rows() > 0) {
    first = series->at("time").front();
    last = series->at("time").back();
  }
  if (particles && !particles->snapshots().empty()) {
    first = std::min(first, particles->snapshots().front().time);
    last = std::max(last, particles->snapshots().back().time);
  }
  return {first, last};
}

}  // namespace

// null when the window held no value
void to_json(Json& j, const WindowStatistics& s) {
  if (s.n == 0)
    j = nullptr;
  else
    j = Json{{"n", s.n}, {"mean", s.mean}, {"sd", s.sd}, {"min", s.min}, {"max", s.max}};
}

BedAnalysis analyseBed(const std::filesystem::path& run, double from, double to) {
  BedAnalysis a;
  a.run = run;
  a.label = runLabel(run);
  if (!std::filesystem::is_directory(run))
    throw InputError("run folder " + run.string() +
                     " does not exist (give the folder a `cosim run` wrote)");
  if (std::filesystem::exists(run / kSummaryFile)) a.summary = readSummary(run / kSummaryFile);
  std::optional<ParticleFile> particles;
  if (std::filesystem::exists(run / kParticlesFile)) particles.emplace(run / kParticlesFile);
  std::optional<TimeSeries> series;
  if (std::filesystem::exists(run / kTimeSeriesFile))
    series.emplace(readTimeSeries(run / kTimeSeriesFile));
  const auto [first, last] = recordSpan(series, particles);
  if (!(last >= first))
    throw InputError(run.string() + " holds neither " + kTimeSeriesFile + " rows nor " +
                     kParticlesFile + " snapshots: nothing to report yet");
  a.from = std::isnan(from) ? first + 0.5 * (last - first) : from;
  a.to = std::isnan(to) ? last : to;
  if (!(a.to > a.from))
    throw InputError(fmt::format(
        "the window [{:g}, {:g}] s is empty: give --fit-start below --fit-end (the run's record "
        "spans {:g} to {:g} s)",
        a.from, a.to, first, last));
  if (series)
    readSeries(*series, run / kTimeSeriesFile, a);
  else
    a.notes.push_back((run / kTimeSeriesFile).string() + " is missing: no pressure drop");
  if (particles)
    readParticles(*particles, a);
  else
    a.notes.push_back((run / kParticlesFile).string() + " is missing: no bed height");
  if (a.pressure_drop.n == 0 && a.snapshots == 0)
    throw InputError(fmt::format(
        "{}: no record in the window [{:g}, {:g}] s (the run's record spans {:g} to {:g} s)",
        run.string(), a.from, a.to, first, last));
  return a;
}

Json toJson(const BedAnalysis& a) {
  Json observables = Json::array();
  if (a.summary)
    for (const auto& o : a.summary->observables) {
      Json e{{"name", o.name}, {"value", o.undefined.empty() ? Json(o.value) : Json(nullptr)}};
      if (!o.undefined.empty()) e.emplace("undefined", o.undefined);
      if (o.reference) e.emplace("reference", *o.reference);
      if (o.relative_error) e.emplace("relative_error", *o.relative_error);
      observables.push_back(std::move(e));
    }
  Json j{{"format", "cosim-report"},
         {"kind", "bed"},
         {"run", a.run.string()},
         {"window_s", {a.from, a.to}},
         {"pressure_drop_pa", a.pressure_drop},
         {"particle_count", a.particle_count},
         {"snapshots", a.snapshots},
         {"bed_height_median_m", a.height_median},
         {"bed_height_p90_m", a.height_p90},
         {"parcel_speed_median_m_s", a.speed_median}};
  if (a.summary) j.emplace("status", a.summary->status);
  j.emplace("observables", std::move(observables));
  j.emplace("notes", a.notes);
  return j;
}

std::string bedReportText(const BedAnalysis& a) {
  auto row = [](const std::string& what, const WindowStatistics& s, double scale,
                const std::string& unit) {
    if (s.n == 0) return fmt::format("| {} | not recorded | | | |\n", what);
    return fmt::format("| {} [{}] | {:.4g} | {:.3g} ({:.1f} %) | {:.4g} | {:.4g} |\n", what, unit,
                       scale * s.mean, scale * s.sd,
                       s.mean != 0 ? 100 * s.sd / std::fabs(s.mean) : 0.0, scale * s.min,
                       scale * s.max);
  };
  std::string t = fmt::format("# {}: the bed over t = {:g} .. {:g} s\n\n", a.label, a.from, a.to);
  if (a.summary)
    t += fmt::format("Scene {}, run {} ({} to {:g} s).\n\n", a.summary->scenario, a.summary->status,
                     a.summary->start_time, a.summary->end_time);
  t += "| quantity | mean | standard deviation (% of the mean) | least | largest |\n"
       "|---|---:|---:|---:|---:|\n";
  t += row("pressure drop across the bed", a.pressure_drop, 1, "Pa");
  t += row("parcels", a.particle_count, 1, "-");
  t += row("bed height: median parcel centre", a.height_median, 1000, "mm");
  t += row("bed top: 90 % of the parcel centres below", a.height_p90, 1000, "mm");
  t += row("median parcel speed", a.speed_median, 1000, "mm/s");
  t += fmt::format(
      "\nHeights and speeds from {} snapshots of particles.h5; the pressure drop from "
      "{} rows of timeseries.csv.\n",
      a.snapshots, a.pressure_drop.n);
  if (a.summary && !a.summary->observables.empty()) {
    t += "\n| observable | value | reference | relative error |\n|---|---:|---:|---:|\n";
    for (const auto& o : a.summary->observables) {
      t += fmt::format(
          "| {} | {} | {} | {} |\n", o.name,
          o.undefined.empty() ? fmt::format("{:.6g}", o.value) : "no value (" + o.undefined + ")",
          o.reference ? fmt::format("{:.6g}", *o.reference) : "",
          o.relative_error ? fmt::format("{:.3g}", *o.relative_error) : "");
    }
  }
  for (const auto& n : a.notes) t += "\nNote: " + n + "\n";
  return t;
}

}  // namespace cosim::analysis
