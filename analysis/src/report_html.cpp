// report.html (one run) and comparison.html (several runs): tables, verdict and the PNGs.
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "cosim/analysis/files.h"
#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

std::string htmlEscape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

namespace {
// A number for a table cell (4 significant digits unless told), a dash when it is not finite.
std::string g(double v, fmt::format_string<double> spec = "{:.4g}") {
  return std::isfinite(v) ? fmt::format(spec, double{v}) : "&ndash;";
}
std::string pct(double v) { return std::isfinite(v) ? g(100.0 * v, "{:.2f}") + " %" : "&ndash;"; }

const char* kStyle =
    "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}td,th{border:1px solid #bbb;padding:3px 8px;"
    "text-align:right}th{background:#eee}td.l,th.l{text-align:left}.ok{color:#186a1e;font-weight:bold}"
    ".bad{color:#a11;font-weight:bold}.note{background:#fff6d6;border:1px solid #e0c060;padding:0.5em}"
    "figure{margin:1em 0}figcaption{font-size:90%;color:#444}img{max-width:100%}</style>\n";

struct Figure {
  const char* file;
  const char* caption;
};
const Figure kRunFigures[] = {
    {"histograms.png", "Histograms of coating mass per parcel at the chosen times, with the normal density of the "
                       "same mean and standard deviation (paper Figs. 6 and 9)."},
    {"statistics_time.png", "Mean coating mass, CV and never-coated share over time."},
    {"cv_mean.png", "CV against mean coated mass (paper Fig. 8)."},
    {"fit.png", "Mean and variance of the coating mass with the fit of Eqs. 9-10 (shaded: fit window), and the "
                "residuals relative to the fit (paper Fig. 10)."},
    {"cv_prediction.png", "Predicted CV = (a2/a1)/sqrt(t) to the horizon, band for the stated error in a2; "
                          "simulated CV as dots (paper Fig. 11)."},
    {"distributions.png", "Reconstructed coating distributions N(a1 t, a2^2 t) (paper Fig. 12)."},
    {"window_study.png", "Error against run time: extrapolated CV and the error of the prediction at the end of the "
                         "run, for fit windows of growing length, against the wall time needed to simulate them."},
    {"mass_balance.png", "Cumulative precursor in, out, held in the gas and coated on particles (paper Fig. 3)."},
    {"zone_passes.png",
     "Passes through the coating zone: passes per parcel (zero: never reached the zone), cycle "
     "time from one entry to the next, and time in the zone per pass (red: mean)."},
};

void figures(std::ostringstream& h, const std::vector<std::string>& pngs, const Figure* list, std::size_t n,
             bool refused = false) {
  for (std::size_t i = 0; i < n; ++i) {
    bool present = false;
    for (const auto& p : pngs) present = present || p == list[i].file;
    if (!present) continue;
    std::string caption = list[i].caption;
    const std::string file = list[i].file;
    if (refused && file == "cv_prediction.png") {
      caption = "Simulated CV with the fitted trend over the simulated times only: no prediction, the run is "
                "poorly mixed (paper Fig. 11).";
    } else if (refused && file == "distributions.png") {
      caption = "Last simulated histogram: no reconstructed distributions, the run is poorly mixed (paper Fig. 12).";
    }
    h << "<figure><img src=\"" << file << "\" alt=\"" << file << "\"><figcaption>" << htmlEscape(caption)
      << "</figcaption></figure>\n";
  }
}

void verdictBlock(std::ostringstream& h, const MixingVerdict& v) {
  h << "<p class=\"" << (v.well_mixed ? "ok" : "bad") << "\">" << htmlEscape(v.well_mixed ? "Well mixed: extrapolation allowed."
                                                                                      : "Poorly mixed: extrapolation refused.")
    << "</p>\n";
  if (!v.relaxed.empty()) {
    h << "<p class=bad>Judged with non-default mixing criteria (cosim report --mixing):</p><ul>";
    for (const auto& r : v.relaxed) h << "<li>" << htmlEscape(r) << "</li>";
    h << "</ul>\n";
  }
  if (!v.reasons.empty()) {
    h << "<ul>";
    for (const auto& r : v.reasons) h << "<li>" << htmlEscape(r) << "</li>";
    h << "</ul>\n";
  }
  if (!v.warnings.empty()) {
    h << "<p>Warnings:</p><ul>";
    for (const auto& w : v.warnings) h << "<li>" << htmlEscape(w) << "</li>";
    h << "</ul>\n";
  }
}
}  // namespace

void writeRunHtml(const RunAnalysis& a, const ReportOptions& o, const std::filesystem::path& dir,
                  const std::vector<std::string>& pngs, const std::string& plot_message) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cosim report: " << htmlEscape(a.label)
    << "</title>\n" << kStyle << "</head><body>\n<h1>Coating report: " << htmlEscape(a.label) << "</h1>\n"
    << "<p>Run folder: <code>" << htmlEscape(a.run.string()) << "</code>. " << a.snapshots.size()
    << " snapshots from t = " << g(a.snapshots.front().time) << " s to " << g(a.snapshots.back().time)
    << " s. Numbers: <a href=\"report.json\">report.json</a> and the CSV tables in this folder.</p>\n";
  if (!plot_message.empty()) h << "<p class=\"note\">Plots missing: " << htmlEscape(plot_message) << "</p>\n";
  if (!a.run_status.empty() && a.run_status != "completed") {
    h << "<p class=\"note\">The run did not complete (summary.json status: " << htmlEscape(a.run_status)
      << "): this report covers what it recorded up to t = " << g(a.snapshots.back().time) << " s.</p>\n";
  }

  h << "<h2>Mixing verdict</h2>\n";
  verdictBlock(h, a.verdict);
  h << zonePassesHtml(a);

  const auto& last = a.snapshots.back();
  h << "<h2>Coating at the end of the run</h2>\n<table><tr><th class=l>quantity</th><th>value</th></tr>"
    << "<tr><td class=l>time [s]</td><td>" << g(last.time) << "</td></tr>"
    << "<tr><td class=l>parcels</td><td>" << last.count << "</td></tr>"
    << "<tr><td class=l>total coating [kg]</td><td>" << g(last.total) << "</td></tr>"
    << "<tr><td class=l>mean per parcel [kg]</td><td>" << g(last.mean) << "</td></tr>"
    << "<tr><td class=l>standard deviation [kg]</td><td>" << g(last.std_dev) << "</td></tr>"
    << "<tr><td class=l>CV</td><td>" << g(last.cv) << "</td></tr>"
    << "<tr><td class=l>never coated (&le; " << g(o.uncoated_relative) << " &times; mean)</td><td>"
    << pct(last.uncoated_share) << "</td></tr></table>\n";

  h << "<h2>Fit of Eqs. 9-10 on [" << g(a.fit.t0) << ", " << g(a.fit.t1) << "] s</h2>\n";
  if (!a.fit.ok) {
    h << "<p class=bad>No fit: " << htmlEscape(a.fit.problem) << "</p>\n";
  } else {
    const double nan = std::nan("");
    h << "<table><tr><th class=l>parameter</th><th>value</th><th>standard error (particle bootstrap)</th>"
         "<th>standard error (regression, HC3)</th><th>standard error (regression, classic)</th></tr>"
         "<tr><td class=l>a1 [kg/s]</td><td>"
      << g(a.fit.a1) << "</td><td>" << g(a.bootstrap.ok ? a.bootstrap.a1_se : nan) << "</td><td>" << g(a.fit.a1_se)
      << "</td><td>" << g(a.fit.a1_se_classic) << "</td></tr><tr><td class=l>a2 [kg/s<sup>0.5</sup>]</td><td>"
      << g(a.fit.a2) << "</td><td>" << g(a.bootstrap.ok ? a.bootstrap.a2_se : nan) << "</td><td>" << g(a.fit.a2_se)
      << "</td><td>" << g(a.fit.a2_se_classic) << "</td></tr></table>\n<p>";
    if (a.bootstrap.ok) {
      h << "Bootstrap: " << a.bootstrap.resamples << " resamples of the " << a.bootstrap.parcels << " parcels over "
        << a.bootstrap.snapshots << " snapshots of the window; it accounts for the snapshots following the same "
        << "parcels, which the regression errors ignore (they are too small for such data). ";
    } else if (!a.bootstrap.problem.empty()) {
      h << "No bootstrap: " << htmlEscape(a.bootstrap.problem) << ". ";
    }
    h << a.fit.tau.size()
      << " snapshots; RMS residual " << pct(a.fit.mean_relative_rms) << " of the mean (mean fit), "
      << pct(a.fit.variance_relative_rms) << " of the mean variance (variance fit). Normality of the last "
      << "snapshot in the window: ";
    if (a.verdict.normality.valid) {
      h << "skewness " << g(a.verdict.normality.skewness, "{:.3f}") << ", excess kurtosis "
        << g(a.verdict.normality.kurtosis - 3.0, "{:.3f}")
        << ", K<sup>2</sup> = " << g(a.verdict.normality.k2)
        << ", p = " << g(a.verdict.normality.p_value, "{:.3g}");
    } else {
      h << htmlEscape(a.verdict.normality.problem);
    }
    h << ".</p>\n";
  }

  if (a.fit.ok) {
    h << "<h2>Extrapolation</h2>\n";
    if (!a.verdict.well_mixed) {
      h << "<p class=bad>Not extrapolated: the run is poorly mixed (see the verdict), so Eqs. 9-10 do not "
           "describe it and a long-time CV from them would be wrong.</p>\n";
    } else {
      h << "<table><tr><th>t [min]</th><th>mean [kg]</th><th>&sigma; [kg]</th><th>CV</th><th>CV "
           "with a2 &minus;"
        << g(100 * o.band, "{:.0f}") << " %</th><th>CV with a2 +" << g(100 * o.band, "{:.0f}")
        << " %</th></tr>";
      std::vector<double> times = o.predict_times;
      times.push_back(o.predict_until);
      for (double t : times) {
        const auto d = predictDistribution(a.fit, t, o.band);
        h << "<tr><td>" << g(t / 60.0) << "</td><td>" << g(d.mean) << "</td><td>" << g(d.sigma)
          << "</td><td>" << g(d.cv) << "</td><td>" << g((1 - o.band) * d.cv) << "</td><td>"
          << g((1 + o.band) * d.cv) << "</td></tr>";
    }
    h << "</table>\n";
    }
    if (!a.prediction_check.points.empty()) {
      const auto& pc = a.prediction_check;
      h << "<p>Prediction checked against the " << pc.points.size() << " simulated snapshots after the fit window "
        << "(to t = " << g(pc.points.back().time) << " s): largest error of the mean " << pct(pc.max_abs_mean_error)
        << ", of &sigma; " << pct(pc.max_abs_std_error) << ", of the CV " << pct(pc.max_abs_cv_error)
        << " (all points in prediction_check.csv).</p>\n";
    } else {
      h << "<p>The run ends with the fit window: no later simulated time to check the prediction against "
           "(run longer than the window, or fit a shorter window, to get the check).</p>\n";
    }
  }

  if (!a.window_study.points.empty()) {
    const auto& w = a.window_study;
    h << "<h2>Error against run time</h2>\n<p>The fit repeated on growing windows: how the extrapolated CV at "
      << g(w.horizon / 60.0) << " min settles, and how well each shorter window predicts the simulated CV at the "
      << "end of the run (t = " << g(w.run_end) << " s, CV = " << g(w.simulated_cv_run_end) << "). Wall time is "
      << "what the simulation needed to reach the end of the window.</p>\n<table><tr><th>window end [s]</th>"
      << "<th>wall time [s]</th><th>a1 [kg/s] &plusmn; HC3</th><th>a2 [kg/s<sup>0.5</sup>] &plusmn; HC3</th><th>CV at "
      << g(w.horizon / 60.0) << " min</th><th>error of the predicted CV at the run end</th></tr>";
    for (const auto& p : w.points) {
      h << "<tr><td>" << g(p.t_end) << "</td><td>" << g(p.wall_seconds) << "</td>";
      if (p.ok) {
        h << "<td>" << g(p.a1) << " &plusmn; " << g(p.a1_se, "{:.2g}") << "</td><td>" << g(p.a2)
          << " &plusmn; " << g(p.a2_se, "{:.2g}") << "</td><td>" << g(p.cv_horizon) << "</td><td>"
          << pct(p.cv_run_end_error) << "</td>";
      } else {
        h << "<td colspan=4>no fit (too few snapshots)</td>";
      }
      h << "</tr>";
    }
    h << "</table>\n";
    if (!a.verdict.well_mixed) h << "<p>The run is poorly mixed: these numbers only show how the fit drifts.</p>\n";
  }

  h << "<h2>Mass balance (paper Table 3)</h2>\n";
  if (a.mass_balance) {
    const auto& b = *a.mass_balance;
    h << "<table><tr><th class=l>quantity</th><th>kg</th></tr>"
      << "<tr><td class=l>precursor in</td><td>" << g(b.precursor_in, "{:.6g}") << "</td></tr>"
      << "<tr><td class=l>precursor out</td><td>" << g(b.precursor_out, "{:.6g}") << "</td></tr>"
      << "<tr><td class=l>held in the gas (change)</td><td>" << g(b.held_change, "{:.6g}")
      << "</td></tr>"
      << "<tr><td class=l>expected coating (in &minus; out &minus; held change)</td><td>"
      << g(b.expected_coating, "{:.6g}") << "</td></tr>"
      << (b.has_removed ? "<tr><td class=l>removed from the gas by the coating sink</td><td>" +
                              g(b.removed, "{:.6g}") + "</td></tr>"
                        : std::string())
      << "<tr><td class=l>coating on particles</td><td>" << g(b.obtained_coating, "{:.6g}")
      << "</td></tr>"
      << "<tr><td class=l>error (expected &minus; obtained)</td><td>" << g(b.error, "{:.3g}")
      << "</td></tr>"
      << "<tr><td class=l>error %</td><td>" << g(b.error_percent, "{:.3g}")
      << "</td></tr></table>\n"
      << "<p>Initial state: " << htmlEscape(b.initial_state)
      << ". Coating on particles: " << htmlEscape(b.obtained_source) << ".</p>\n";
    if (b.has_removed && std::abs(b.pending) > 1e-9 * std::abs(b.removed)) {
      h << "<p class=note>" << g(b.pending, "{:.3g}")
        << " kg removed from the gas is not on the particles "
        << "(removed minus coating on particles). If the coating was read from timeseries.csv, the "
           "last step's "
        << "credit comes after its last row; otherwise coating was lost between the fluid and the "
           "particles.</p>\n";
    }
  } else {
    h << "<p>" << htmlEscape(a.mass_balance_problem) << "</p>\n";
  }
  if (std::isfinite(a.wall_seconds)) {
    h << "<p>Run time: " << g(a.wall_seconds) << " s wall clock over " << a.steps << " coupling steps ("
      << g(a.wall_seconds / static_cast<double>(a.steps > 0 ? a.steps : 1)) << " s per step).</p>\n";
  }

  h << "<h2>Figures</h2>\n";
  figures(h, pngs, kRunFigures, std::size(kRunFigures), !a.verdict.well_mixed);

  h << "<h2>Statistics over time</h2>\n<table><tr><th>t [s]</th><th>parcels</th><th>mean [kg]</th><th>&sigma; "
       "[kg]</th><th>CV</th><th>never coated</th></tr>";
  const std::size_t n = a.snapshots.size();
  const std::size_t stride = n > 25 ? (n + 24) / 25 : 1;
  for (std::size_t i = 0; i < n; i += stride) {
    const auto& s = a.snapshots[i];
    h << "<tr><td>" << g(s.time) << "</td><td>" << s.count << "</td><td>" << g(s.mean) << "</td><td>" << g(s.std_dev)
      << "</td><td>" << g(s.cv) << "</td><td>" << pct(s.uncoated_share) << "</td></tr>";
  }
  h << "</table>\n<p>Every snapshot: statistics.csv.</p>\n</body></html>\n";
  writeFileAtomically(dir / "report.html", h.str());
}

namespace {
const Figure kComparisonFigures[] = {
    {"compare_cv_mean.png", "CV against mean coated mass for every run (paper Fig. 8)."},
    {"compare_statistics_time.png", "Mean coating mass and CV over time for every run."},
    {"compare_histograms.png", "Coating histograms at the end of every run (paper Fig. 6)."},
};
}  // namespace

void writeComparisonHtml(const std::vector<RunAnalysis>& runs, const std::vector<std::string>& folders,
                         const std::filesystem::path& dir, const std::vector<std::string>& pngs,
                         const std::string& plot_message) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cosim comparison report</title>\n" << kStyle
    << "</head><body>\n<h1>Coating comparison of " << runs.size() << " runs</h1>\n";
  if (!plot_message.empty()) h << "<p class=\"note\">Plots missing: " << htmlEscape(plot_message) << "</p>\n";
  const auto varied = variedParameters(runs);
  h << "<table><tr><th class=l>run</th>";
  for (const auto& n : varied) h << "<th>" << htmlEscape(n) << "</th>";
  h << "<th>end [s]</th><th>total coating [kg]</th><th>mean [kg]</th><th>CV</th>"
       "<th>never coated</th><th>never in the zone</th><th>mean cycle [s]</th>"
       "<th>a1 [kg/s]</th><th>a2 [kg/s<sup>0.5</sup>]</th><th>CV at 20 min</th>"
       "<th>mass balance error %</th><th>wall time [s]</th><th class=l>verdict</th></tr>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& a = runs[i];
    const auto& l = a.snapshots.back();
    h << "<tr><td class=l><a href=\"" << htmlEscape(folders[i]) << "/report.html\">" << htmlEscape(a.label)
      << "</a></td>";
    for (const auto& n : varied) h << "<td>" << g(parameter(a, n), "{:.6g}") << "</td>";
    h << "<td>" << g(l.time) << "</td><td>" << g(l.total) << "</td><td>" << g(l.mean) << "</td><td>"
      << g(l.cv) << "</td><td>" << pct(l.uncoated_share) << "</td><td>"
      << (a.zone_passes ? pct(a.zone_passes->stats.never_entered_share) : "&ndash;") << "</td><td>"
      << (a.zone_passes ? g(a.zone_passes->stats.cycle_time.mean, "{:.3g}") : "&ndash;")
      << "</td><td>"
      << (a.fit.ok ? g(a.fit.a1) + " &plusmn; " + g(a.a1Error(), "{:.2g}") : "&ndash;")
      << "</td><td>"
      << (a.fit.ok ? g(a.fit.a2) + " &plusmn; " + g(a.a2Error(), "{:.2g}") : "&ndash;")
      << "</td><td>"
      << (a.fit.ok && a.verdict.well_mixed ? g(predictDistribution(a.fit, 1200.0).cv) : "&ndash;")
      << "</td><td>" << (a.mass_balance ? g(a.mass_balance->error_percent, "{:.3g}") : "&ndash;")
      << "</td><td>" << g(a.wall_seconds) << "</td><td class=l><span class="
      << (a.verdict.well_mixed ? "ok>well mixed" : "bad>poorly mixed") << "</span>";
    for (const auto& r : a.verdict.reasons) h << "<br>" << htmlEscape(r);
    h << "</td></tr>\n";
  }
  h << "</table>\n<p>Per-run reports: follow the links. Numbers: comparison.json, comparison.csv.</p>\n";
  figures(h, pngs, kComparisonFigures, std::size(kComparisonFigures));
  h << "</body></html>\n";
  writeFileAtomically(dir / "comparison.html", h.str());
}

}  // namespace cosim::analysis
