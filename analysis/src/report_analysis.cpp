// analyseRun: every number of one run's report, computed from its recorded files.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/report.h"
#include "cosim/analysis/summary.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "report_internal.h"

namespace cosim::analysis {

std::string runLabel(const std::filesystem::path& run) {
  auto p = run.lexically_normal();
  if (p.has_filename()) return p.filename().string();
  return p.parent_path().filename().string();
}

namespace {
// The run's status and scenario parameters (a sweep's comparison shows what differs), and the cg
// it used, from summary.json when there is one.
std::optional<double> readRunSummary(const std::filesystem::path& run, RunAnalysis& a) {
  if (!std::filesystem::exists(run / kSummaryFile)) return std::nullopt;
  try {
    const Summary summary = readSummary(run / kSummaryFile);
    a.run_status = summary.status;
    a.parameters = summary.parameters;
    return summary.cg;
  } catch (const std::exception& e) {
    throw Error(kindOf(e, ErrorKind::input),
                std::string(e.what()) + "; move it away to report the run without it");
  }
}

// The snapshot nearest to each requested histogram time (default: a quarter, half, three
// quarters and all of the record).
std::vector<std::size_t> nearestSnapshots(const std::vector<SnapshotInfo>& snaps,
                                          std::vector<double>& wanted) {
  if (wanted.empty()) {
    const double first = snaps.front().time, last = snaps.back().time;
    for (double f : {0.25, 0.5, 0.75, 1.0}) wanted.push_back(first + f * (last - first));
  }
  std::vector<std::size_t> nearest;
  for (double t : wanted) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < snaps.size(); ++i) {
      if (std::abs(snaps[i].time - t) < std::abs(snaps[best].time - t)) best = i;
    }
    nearest.push_back(best);
  }
  return nearest;
}

// Snapshots kept per parcel for the bootstrap: at most bootstrap_snapshots, evenly spread over
// the fitted ones (1 = kept).
std::vector<char> bootstrapSnapshots(const std::vector<SnapshotInfo>& snaps, double t0, double t1,
                                     const ReportOptions& o) {
  std::vector<std::size_t> fitted;
  for (std::size_t i = 0; i < snaps.size(); ++i) {
    if (snaps[i].time >= t0 && snaps[i].time <= t1 && snaps[i].time > o.coating_start &&
        snaps[i].count > 0) {
      fitted.push_back(i);
    }
  }
  std::vector<char> keep(snaps.size(), 0);
  if (o.bootstrap_resamples > 0 && !fitted.empty()) {
    const std::size_t k = std::min(fitted.size(), std::max<std::size_t>(o.bootstrap_snapshots, 3));
    for (std::size_t j = 0; j < k; ++j) {
      keep[fitted[k == 1 ? 0 : j * (fitted.size() - 1) / (k - 1)]] = 1;
    }
  }
  return keep;
}

// Every snapshot's statistics, the histograms asked for, and the kept snapshots' coating per
// parcel (one column per parcel, NaN where a parcel is absent) for the bootstrap.
ParcelHistories readSnapshots(const ParticleFile& file, const ReportOptions& o,
                              const std::vector<char>& keep, RunAnalysis& a) {
  const auto& snaps = file.snapshots();
  std::vector<double> wanted = o.histogram_times;
  const auto nearest = nearestSnapshots(snaps, wanted);
  a.histograms.resize(wanted.size());
  ParcelHistories histories;
  std::unordered_map<std::int64_t, std::size_t> column;
  std::vector<std::pair<std::vector<std::int64_t>, std::vector<double>>> kept;
  for (std::size_t i = 0; i < snaps.size(); ++i) {
    std::vector<double> m = file.read(i, cosim::field::coating_mass);
    a.snapshots.push_back(coatingStatistics(snaps[i].time, m, o.uncoated_relative));
    for (std::size_t h = 0; h < wanted.size(); ++h) {
      if (nearest[h] == i) {
        a.histograms[h].requested = wanted[h];
        a.histograms[h].stats = a.snapshots.back();
        a.histograms[h].histogram = histogram(m);
      }
    }
    if (keep[i]) {
      auto ids = file.ids(i);
      for (auto id : ids) column.emplace(id, column.size());
      histories.time.push_back(snaps[i].time);
      kept.emplace_back(std::move(ids), std::move(m));
    }
  }
  for (const auto& [ids, m] : kept) {
    std::vector<double> row(column.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t j = 0; j < ids.size(); ++j) row[column.at(ids[j])] = m[j];
    histories.mass.push_back(std::move(row));
  }
  return histories;
}

// The verdict on the last snapshot of the fit window (what the fit saw), with the window's
// snapshots telling a skewed distribution on its way to normal (a well-mixed bed's skewness falls
// as t^-1/2) from one that stays skewed.
MixingVerdict judgeRun(const ParticleFile& file, const RunAnalysis& a, double t0, double t1,
                       const ReportOptions& o) {
  const auto& snaps = file.snapshots();
  std::size_t lastInWindow = snaps.size() - 1;
  for (std::size_t i = snaps.size(); i-- > 0;) {
    if (snaps[i].time <= t1) {
      lastInWindow = i;
      break;
    }
  }
  const std::vector<double> values = file.read(lastInWindow, cosim::field::coating_mass);
  NormalityHistory history;
  history.coating_start = o.coating_start;
  history.predict_at = o.predict_times.empty()
                           ? o.predict_until
                           : *std::min_element(o.predict_times.begin(), o.predict_times.end());
  for (std::size_t i = 0; i <= lastInWindow; ++i) {
    if (a.snapshots[i].time >= t0 && a.snapshots[i].time > o.coating_start)
      history.snapshots.push_back(a.snapshots[i]);
  }
  return judgeMixing(a.fit, a.snapshots[lastInWindow], values, o.criteria, history);
}

// From timeseries.csv: the fit-window study with wall times, the run's steps and wall time, and
// the precursor balance (with the coating on the particles themselves when particles.h5 holds
// the state at the end of the series and an initial state before its first row).
void readTimeSeriesChecks(const std::filesystem::path& run, const ParticleFile& file, double t0,
                          const ReportOptions& o, RunAnalysis& a) {
  const auto tsPath = run / kTimeSeriesFile;
  const double horizon = o.predict_times.empty() ? o.predict_until : o.predict_times.back();
  if (!std::filesystem::exists(tsPath)) {
    a.mass_balance_problem = tsPath.string() + " is missing: no mass balance";
    a.window_study = studyFitWindow(a.snapshots, t0, o.coating_start, horizon);
    return;
  }
  TimeSeries ts = readTimeSeries(tsPath);
  a.window_study = studyFitWindow(a.snapshots, t0, o.coating_start, horizon, &ts);
  a.steps = ts.rows();
  if (ts.has(column::wall_seconds) && ts.rows() > 0)
    a.wall_seconds = ts.at(column::wall_seconds).back();
  try {
    a.mass_balance = massBalance(ts);
    const auto& times = ts.at(column::time);
    const double tEnd = times.back();
    const double tol = 1e-9 * std::max(1.0, std::abs(tEnd));
    if (a.snapshots.size() >= 2 && std::abs(a.snapshots.back().time - tEnd) <= tol &&
        a.snapshots.front().time < times.front() - tol) {
      const auto& first = a.snapshots.front();
      const auto& lastSnap = a.snapshots.back();
      a.mass_balance = withParticleCoating(
          *a.mass_balance, first.total, lastSnap.total,
          file.path().string() + ": sum of coating_mass at t = " + std::to_string(lastSnap.time) +
              " s minus at t = " + std::to_string(first.time) + " s");
    }
  } catch (const std::exception& e) {
    a.mass_balance_problem = std::string("no mass balance: ") + e.what();
  }
}
}  // namespace

RunAnalysis analyseRun(const std::filesystem::path& run, const ReportOptions& o) {
  RunAnalysis a;
  a.run = run;
  a.label = runLabel(run);
  if (!std::filesystem::is_directory(run)) {
    throw InputError("run folder " + run.string() +
                     " does not exist (give the folder a `cosim run` wrote, "
                     "e.g. runs/plasma-coating-bed)");
  }
  const std::optional<double> cg = readRunSummary(run, a);  // what the run used
  ParticleFile file(run / kParticlesFile);
  if (!file.hasField(cosim::field::coating_mass)) {
    throw InputError(file.path().string() +
                     " has no coating_mass field: this scene has no coating "
                     "(no mass_transfer model), and cosim report analyses coating. The "
                     "run's own records describe its bed: timeseries.csv (pressure_drop, "
                     "particle_count), summary.json (observables), particles.xmf in "
                     "ParaView, and `cosim piv " +
                     run.string() + "` for the particle velocity at the front wall");
  }
  const auto& snaps = file.snapshots();
  if (snaps.empty()) throw InputError(file.path().string() + " holds no snapshot yet");
  const double t0 = std::isnan(o.fit_start) ? snaps.front().time : o.fit_start;
  const double t1 = std::isnan(o.fit_end) ? snaps.back().time : o.fit_end;
  if (t1 <= t0) {
    throw InputError("fit window [" + std::to_string(t0) + ", " + std::to_string(t1) +
                     "] s is empty: give --fit-start below --fit-end");
  }

  const ParcelHistories histories = readSnapshots(file, o, bootstrapSnapshots(snaps, t0, t1, o), a);
  a.fit = fitGrowth(a.snapshots, t0, t1, o.coating_start);
  if (a.fit.ok && histories.time.size() >= 3)
    a.bootstrap = bootstrapGrowthErrors(histories, o.coating_start, o.bootstrap_resamples);
  a.verdict = judgeRun(file, a, t0, t1, o);
  if (a.fit.ok) {
    // The extrapolation is computed whenever a fit exists (the check against later simulated
    // times is what tells a user how far to trust it); the report shows it only as a prediction
    // when the verdict allows it.
    a.cv_prediction = predictCv(a.fit, o.predict_until, 200, o.band);
    for (double t : o.predict_times)
      a.distributions.push_back(predictDistribution(a.fit, t, o.band));
    a.prediction_check = checkPrediction(a.fit, a.snapshots);
  }
  readTimeSeriesChecks(run, file, t0, o, a);
  a.zone_passes = analyseZonePasses(run, file, a, o, a.zone_passes_problem);
  a.batch = analyseBatch(file, o, a.batch_problem);
  a.conditions = readOperatingConditions(
      {run, a.parameters, cg, o.coating_start, o.coating_density, o.u_mf}, file);
  std::vector<RunAnalysis> one;
  one.push_back(std::move(a));
  chooseDisplayUnits(one);
  return std::move(one.front());
}

void chooseDisplayUnits(std::vector<RunAnalysis>& runs) {
  double mean = 0, thickness = 0;
  for (const auto& r : runs) {
    for (const auto& s : r.snapshots) {
      if (!(std::isfinite(s.mean) && s.mean > 0)) continue;
      mean = std::max(mean, s.mean);
      const double h = r.conditions.grain.thickness(s.mean);
      if (std::isfinite(h)) thickness = std::max(thickness, h);
    }
  }
  for (auto& r : runs) {
    r.mass_unit = massUnitFor(mean);
    r.thickness_unit = lengthUnitFor(thickness);
  }
}

}  // namespace cosim::analysis
