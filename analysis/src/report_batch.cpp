// The whole batch in a run's report: the long-time model (long_time.h) with cosim batch's
// defaults, from the run's own snapshots to ReportOptions::predict_until.
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "cosim/analysis/display_units.h"
#include "cosim/analysis/long_time.h"
#include "cosim/analysis/long_time_check.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
// The model fitted on the record's first half, held against the run's snapshots of the second
// (at a quarter, half, three quarters of the way and at the end); none for a record of fewer than
// 6 snapshots.
std::optional<LongTimeCheck> checkOnSecondHalf(const ParticleFile& file, const CoatingDatabase& db,
                                               double& record_to) {
  const std::size_t n = db.times.size();
  if (n < 6) return std::nullopt;
  const std::size_t mid = (n - 1) / 2;
  record_to = db.times[mid];
  const auto first = readCoatingDatabase(file, db.times.front(), record_to, db.grid);
  std::vector<double> times;
  for (const std::size_t k :
       {mid + (n - 1 - mid) / 4, mid + (n - 1 - mid) / 2, mid + 3 * (n - 1 - mid) / 4, n - 1})
    if (k > mid && (times.empty() || db.times[k] > times.back())) times.push_back(db.times[k]);
  return checkLongTime(fitLongTimeModel(first), first, readRecordedCoating(file, times), 1);
}
}  // namespace

std::optional<BatchPrediction> analyseBatch(const ParticleFile& file, const ReportOptions& o,
                                            std::string& problem) {
  if (!o.batch) {
    problem = "not asked for (--no-batch)";
    return std::nullopt;
  }
  try {
    const auto db = readCoatingDatabase(file, 0, -1, Compartments{});
    const auto model = fitLongTimeModel(db);
    std::vector<double> times = {db.times.back()};
    for (double t : {20.0, 60.0, 300.0, 1200.0, 3600.0})
      if (t > db.times.back() && t <= o.predict_until) times.push_back(t);
    const auto pr = predictLongTime(model, db, times, 1);
    BatchPrediction b;
    b.record_from = db.times.front();
    b.record_to = db.times.back();
    b.longest_wait = model.longest_wait_seconds;
    b.mixing = model.mixing_seconds;
    b.warnings = model.warnings;
    for (const auto& p : pr.points) {
      b.times.push_back(p.time);
      b.mean.push_back(p.mean);
      b.cv.push_back(p.cv);
      b.never_coated.push_back(p.never_coated_share);
    }
    b.wall_seconds = pr.wall_seconds;
    b.check = checkOnSecondHalf(file, db, b.check_record_to);
    return b;
  } catch (const std::exception& e) {
    problem = e.what();
    return std::nullopt;
  }
}

namespace {
Json checkJson(const BatchPrediction& b) {
  if (!b.check) return nullptr;
  Json j{{"record_to_s", b.check_record_to}};
  j.update(Json(*b.check));
  return j;
}

std::string checkHtml(const RunAnalysis& a) {
  const auto& b = *a.batch;
  if (!b.check || b.check->rows.empty()) return "";
  std::ostringstream h;
  h << "<p>How far to trust it on this bed: the same model fitted on the record up to "
    << htmlNumber(b.check_record_to, 4)
    << " s only, held against what the run itself recorded after that.</p>\n"
       "<table>\n<tr><th>time [s]</th><th>mean, model ["
    << a.mass_unit.name
    << "]</th><th>mean, run</th><th>error [%]</th><th>CV, model</th><th>CV, run</th>"
       "<th>error [%]</th><th>never coated, model [%]</th><th>never coated, run [%]</th>"
       "<th>difference [points]</th></tr>\n";
  for (const auto& r : b.check->rows)
    h << "<tr><td>" << htmlNumber(r.time, 6) << "</td><td>"
      << htmlNumber(a.mass_unit.of(r.predicted.mean)) << "</td><td>"
      << htmlNumber(a.mass_unit.of(r.recorded.mean)) << "</td><td>"
      << fmt::format("{:+.1f}", 100 * r.mean_error) << "</td><td>" << htmlNumber(r.predicted.cv)
      << "</td><td>" << htmlNumber(r.recorded.cv) << "</td><td>"
      << fmt::format("{:+.1f}", 100 * r.cv_error) << "</td><td>"
      << htmlNumber(100 * r.predicted.never_coated_share, 3) << "</td><td>"
      << htmlNumber(100 * r.recorded.never_coated_share, 3) << "</td><td>"
      << fmt::format("{:+.2f}", r.never_points) << "</td></tr>\n";
  h << "</table>\n"
    << fmt::format(
           "<p>The parcels' coating at the last time: Kolmogorov-Smirnov distance {:.3g} between "
           "the model's and the run's (two independent samples of this size exceed {:.3g} one "
           "time in twenty).</p>\n",
           b.check->ks_distance, b.check->ks_critical);
  return h.str();
}
}  // namespace

Json batchJson(const RunAnalysis& a) {
  if (!a.batch) return Json{{"computed", false}, {"problem", a.batch_problem}};
  const auto& b = *a.batch;
  return Json{{"computed", true},
              {"record_from_s", b.record_from},
              {"record_to_s", b.record_to},
              {"longest_wait_s", b.longest_wait},
              {"mixing_s", b.mixing},
              {"warnings", b.warnings},
              {"times_s", b.times},
              {"mean_kg", b.mean},
              {"cv", b.cv},
              {"never_coated_share", b.never_coated},
              {"wall_s", b.wall_seconds},
              {"check_on_second_half", checkJson(b)}};
}

std::string batchHtml(const RunAnalysis& a) {
  std::ostringstream h;
  h << "<h2>The whole batch (long-time model)</h2>\n";
  if (!a.batch) {
    h << "<p>No long-time prediction: " << htmlEscape(a.batch_problem) << ".</p>\n";
    return h.str();
  }
  const auto& b = *a.batch;
  h << "<p>Every parcel carried on from the record's end between compartments of the bed, with "
       "the coating gains the record holds for each move (<code>cosim batch</code>; "
       "docs/physics.md, section 5b). Unlike Eqs. 9-10 it holds for a poorly mixed bed too. "
    << fmt::format(
           "Record {:.3g}-{:.3g} s; the longest wait for the zone {:.3g} s. The first row "
           "is the record's own end.",
           b.record_from, b.record_to, b.longest_wait)
    << "</p>\n";
  if (!b.warnings.empty()) {
    h << "<ul>\n";
    for (const auto& w : b.warnings) h << "<li><b>Caution:</b> " << htmlEscape(w) << ".</li>\n";
    h << "</ul>\n";
  }
  h << "<table>\n<tr><th>time [s]</th><th>mean per parcel [" << a.mass_unit.name
    << "]</th><th>CV</th><th>never coated [%]</th></tr>\n";
  for (std::size_t i = 0; i < b.times.size(); ++i) {
    h << "<tr><td>" << htmlNumber(b.times[i], 6) << "</td><td>"
      << htmlNumber(a.mass_unit.of(b.mean[i])) << "</td><td>" << htmlNumber(b.cv[i]) << "</td><td>"
      << htmlNumber(100 * b.never_coated[i], 3) << "</td></tr>\n";
  }
  h << "</table>\n" << checkHtml(a);
  return h.str();
}

}  // namespace cosim::analysis
