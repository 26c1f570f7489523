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

std::optional<BatchPrediction> analyseBatch(const ParticleFile& file, const ReportOptions& o,
                                            std::string& problem) {
  if (!o.batch) {
    problem = "not asked for (--no-batch)";
    return std::nullopt;
  }
  try {
    auto choice = chooseCompartments(file, 0, -1);
    const auto db = readCoatingDatabase(file, 0, -1, choice.chosen);
    auto model = fitLongTimeModel(db, choice.lag);
    std::vector<double> times = {db.times.back()};
    for (double t : {20.0, 60.0, 300.0, 1200.0, 3600.0})
      if (t > db.times.back() && t <= o.predict_until) times.push_back(t);
    warnWhenTheBedOutlastsTheBatch(model, db.times.back(), times.back());
    const auto pr = predictLongTime(model, db, times, 1);
    BatchPrediction b;
    b.record_from = db.times.front();
    b.record_to = db.times.back();
    b.longest_wait = model.longest_wait_seconds;
    b.mixing = model.mixing_seconds;
    b.dead_end_moves = model.dead_end_moves;
    b.warnings = model.warnings;
    for (const auto& p : pr.points) {
      b.times.push_back(p.time);
      b.mean.push_back(p.mean);
      b.cv.push_back(p.cv);
      b.never_coated.push_back(p.never_coated_share);
    }
    b.wall_seconds = pr.wall_seconds;
    b.grid = choice.chosen;
    b.step = model.interval;
    b.grid_trials = std::move(choice.trials);
    for (std::size_t i = 0; i < b.grid_trials.size(); ++i)
      if (b.grid_trials[i].grid.rings == b.grid.rings &&
          b.grid_trials[i].grid.layers == b.grid.layers && b.grid_trials[i].lag == choice.lag)
        b.chosen = i;
    return b;
  } catch (const std::exception& e) {
    problem = e.what();
    return std::nullopt;
  }
}

namespace {

std::string checkHtml(const RunAnalysis& a) {
  const auto& b = *a.batch;
  if (b.grid_trials.empty()) return "";
  std::ostringstream h;
  h << "<p>How far to trust it on this bed, and the compartments and step it uses: each grid's "
       "model, at each step, fitted on the record's first half only (to "
    << htmlNumber(b.grid_trials.front().half.record_to, 4)
    << " s), held against what the run itself recorded at its end; and each fitted on half the "
       "parcels over the whole record, carrying the other half from the record's start to its "
       "end (held out). The batch above uses the model whose parcels' coating is closest to the "
       "run's in both checks (the larger of the two Kolmogorov-Smirnov distances, each over the "
       "distance two independent samples exceed one time in twenty, least) among those whose "
       "chain settles to the record's coating rate.</p>\n"
       "<table>\n<tr><th>rings x layers</th><th>step [s]</th><th>mean error [%]</th><th>CV error "
       "[%]</th>"
       "<th>never coated, difference [points]</th><th>Kolmogorov-Smirnov</th>"
       "<th>5 % of independent samples exceed</th><th>held out: CV error [%]</th>"
       "<th>held out: never coated [points]</th><th>held out: Kolmogorov-Smirnov</th>"
       "<th>wall [s]</th></tr>\n";
  for (std::size_t i = 0; i < b.grid_trials.size(); ++i) {
    const auto& t = b.grid_trials[i];
    const auto& r = t.half.check.rows.back();
    const bool used = b.chosen && *b.chosen == i;
    h << "<tr><td>" << t.grid.rings << "x" << t.grid.layers << (used ? "&nbsp;(used)" : "")
      << (t.half.settles_off ? "&nbsp;(settles off the record's rate)" : "") << "</td><td>"
      << htmlNumber(t.half.step, 3) << "</td><td>" << fmt::format("{:+.1f}", 100 * r.mean_error)
      << "</td><td>" << fmt::format("{:+.1f}", 100 * r.cv_error) << "</td><td>"
      << fmt::format("{:+.2f}", r.never_points) << "</td><td>"
      << htmlNumber(t.half.check.ks_distance, 3) << "</td><td>"
      << htmlNumber(t.half.check.ks_critical, 3) << "</td><td>";
    if (t.held_out && !t.held_out->rows.empty())
      h << fmt::format("{:+.1f}", 100 * t.held_out->rows.back().cv_error) << "</td><td>"
        << fmt::format("{:+.2f}", t.held_out->rows.back().never_points) << "</td><td>"
        << htmlNumber(t.held_out->ks_distance, 3) << "</td><td>";
    else
      h << "-</td><td>-</td><td>-</td><td>";
    h << htmlNumber(t.half.wall_seconds, 3) << "</td></tr>\n";
  }
  h << "</table>\n";
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
              {"dead_end_moves", b.dead_end_moves},
              {"warnings", b.warnings},
              {"times_s", b.times},
              {"mean_kg", b.mean},
              {"cv", b.cv},
              {"never_coated_share", b.never_coated},
              {"wall_s", b.wall_seconds},
              {"rings", b.grid.rings},
              {"layers", b.grid.layers},
              {"step_s", b.step},
              {"check_on_second_half", b.grid_trials}};
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
           "Record {:.3g}-{:.3g} s; {} x {} compartments (rings x layers), steps of {:.3g} s; the "
           "longest wait for the zone {:.3g} s. The first row is the record's own end.",
           b.record_from, b.record_to, b.grid.rings, b.grid.layers, b.step, b.longest_wait)
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
