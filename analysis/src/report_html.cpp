// report.html (one run) and comparison.html (several runs). A page opens with the operating
// conditions, then the verdict in words, then the evidence; the statistical detail (regression
// and bootstrap errors, normality and runs tests, error against run time, every snapshot) is
// folded below it. Every coating mass is in the report's one mass unit (a.mass_unit); numbers
// in table cells never break across lines. docs/analysis.md section 8.
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "cosim/analysis/display_units.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

std::string htmlEscape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

namespace {
std::string mass(const RunAnalysis& a, double kg, int digits = 4) {
  return htmlNumber(a.mass_unit.of(kg), digits);
}
std::string layer(const RunAnalysis& a, double parcel_kg) {
  return htmlNumber(a.thickness_unit.of(a.conditions.grain.thickness(parcel_kg)), 3);
}
std::string perGrain(const RunAnalysis& a, double parcel_kg) {
  return htmlNumber(a.mass_unit.of(a.conditions.grain.perGrain(parcel_kg)), 4);
}
std::string unit(const DisplayUnit& u, const char* per = "") { return "[" + u.name + per + "]"; }

const char* kStyle =
    "<style>body{font-family:sans-serif;max-width:1150px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}td,th{border:1px solid #bbb;padding:3px "
    "8px;"
    "text-align:right}td{white-space:nowrap}th{background:#eee}td.l,th.l{text-align:left;white-"
    "space:normal}"
    ".ok{color:#186a1e;font-weight:bold}.bad{color:#a11;font-weight:bold}"
    "p.verdict{font-size:115%;padding:0.6em;border-left:6px "
    "solid}p.verdict.ok{border-color:#186a1e;"
    "background:#eef8ee}p.verdict.bad{border-color:#a11;background:#fbeeee}"
    ".note{background:#fff6d6;border:1px solid #e0c060;padding:0.5em}"
    "div.hypothetical{border:2px dashed #a0a0a0;padding:0 0.8em;margin:1em 0;background:#f6f6f6}"
    "details{margin:1.5em 0;border:1px solid #ccc;padding:0.3em "
    "0.8em}summary{font-weight:bold;cursor:pointer}"
    "figure{margin:1em 0}figcaption{font-size:90%;color:#444}img{max-width:100%}</style>\n";

struct Figure {
  const char* file;
  const char* caption;
};
const Figure kRunFigures[] = {
    {"histograms.png",
     "Histograms of coating mass per parcel at the chosen times, with the normal density of the "
     "same mean and standard deviation (paper Figs. 6 and 9)."},
    {"statistics_time.png", "Mean coating mass, CV and never-coated share over time."},
    {"cv_mean.png", "CV against mean coated mass (paper Fig. 8)."},
    {"fit.png",
     "Mean and standard deviation of the coating mass with the fit of Eqs. 9-10 (a1 t and a2 "
     "sqrt(t); "
     "shaded: fit window), and the residuals of the mean and variance fits relative to the data "
     "(paper "
     "Fig. 10)."},
    {"cv_prediction.png",
     "Predicted CV = (a2/a1)/sqrt(t) to the horizon, band for the stated error in a2; "
     "simulated CV as dots (paper Fig. 11)."},
    {"distributions.png", "Reconstructed coating distributions N(a1 t, a2^2 t) (paper Fig. 12)."},
    {"window_study.png",
     "Error against run time: extrapolated CV and the error of the prediction at the end of the "
     "run, for fit windows of growing length, against the wall time needed to simulate them."},
    {"mass_balance.png",
     "Cumulative precursor in, out, held in the gas and coated on particles (paper Fig. 3)."},
    {"zone_passes.png",
     "Passes through the coating zone: passes per parcel (zero: never reached the zone), cycle "
     "time from one entry to the next, and time in the zone per pass (red: mean)."},
};

void figures(std::ostringstream& h, const std::vector<std::string>& pngs, const Figure* list,
             std::size_t n, bool refused = false) {
  for (std::size_t i = 0; i < n; ++i) {
    bool present = false;
    for (const auto& p : pngs) present = present || p == list[i].file;
    if (!present) continue;
    std::string caption = list[i].caption;
    const std::string file = list[i].file;
    if (refused && file == "cv_prediction.png") {
      caption =
          "Simulated CV with the fitted trend over the simulated times only: no prediction, the "
          "run is "
          "poorly mixed (paper Fig. 11).";
    } else if (refused && file == "distributions.png") {
      caption =
          "Last simulated histogram: no reconstructed distributions, the run is poorly mixed "
          "(paper Fig. 12).";
    } else if (refused && file == "window_study.png") {
      caption =
          "Error of the CV predicted at the end of the run by fit windows of growing length, "
          "against the "
          "wall time needed to simulate them (no extrapolated CV: the run is poorly mixed).";
    }
    h << "<figure><img src=\"" << file << "\" alt=\"" << file << "\"><figcaption>"
      << htmlEscape(caption) << "</figcaption></figure>\n";
  }
}

void row(std::ostringstream& h, const std::string& quantity, const std::string& value,
         const std::string& source) {
  h << "<tr><td class=l>" << quantity << "</td><td>" << value << "</td><td class=l>"
    << htmlEscape(source) << "</td></tr>";
}

void conditionsTable(std::ostringstream& h, const RunAnalysis& a) {
  const auto& c = a.conditions;
  h << "<h2>Operating conditions</h2>\n<table><tr><th class=l>condition</th><th>value</th>"
       "<th class=l>from</th></tr>";
  if (std::isfinite(c.flow_lpm)) {
    row(h, "fluidization gas flow", htmlNumber(c.flow_lpm) + "&nbsp;L/min",
        "scene parameter flow_lpm");
  }
  if (std::isfinite(c.superficial_velocity)) {
    row(h, "superficial gas velocity u", htmlNumber(c.superficial_velocity, 3) + "&nbsp;m/s",
        "scene parameter " + c.superficial_velocity_parameter);
  }
  if (std::isfinite(c.u_mf)) {
    row(h, "minimum fluidization velocity u<sub>mf</sub>", htmlNumber(c.u_mf, 3) + "&nbsp;m/s",
        c.u_mf_source);
    if (std::isfinite(c.superficial_velocity))
      row(h, "u / u<sub>mf</sub>", htmlNumber(c.uOverUmf(), 3), "");
  }
  if (std::isfinite(c.nozzle_velocity)) {
    row(h, "nozzle gas velocity", htmlNumber(c.nozzle_velocity, 3) + "&nbsp;m/s",
        "scene parameter u_nozzle");
  }
  if (std::isfinite(c.precursor_fraction)) {
    row(h, "precursor mass fraction in the nozzle gas", htmlNumber(c.precursor_fraction, 3),
        "scene parameter Y_nozzle");
  }
  row(h, "parcels", std::to_string(c.parcels), "particles.h5, last snapshot");
  row(h, "coarse-graining factor cg", htmlNumber(c.grain.cg, 3),
      c.cg_source + "; a parcel stands for cg^3 = " + fmt::format("{:g}", std::pow(c.grain.cg, 3)) +
          " real grains");
  if (std::isfinite(c.parcel_diameter)) {
    row(h, "parcel diameter / real grain diameter",
        htmlQuantity(c.parcel_diameter, lengthUnitFor(c.parcel_diameter), 3) + "&nbsp;/&nbsp;" +
            htmlQuantity(c.grain.grain_diameter, lengthUnitFor(c.grain.grain_diameter), 3),
        c.parcel_diameter_source + "; real grain = parcel / cg");
  }
  row(h, "coating time", htmlDuration(c.coating_time),
      "t = " + fmt::format("{:g}", a.snapshots.front().time) + " to " +
          fmt::format("{:g}", a.snapshots.back().time) + " s recorded");
  row(h, "coating density (for the layer thickness)",
      htmlNumber(c.grain.coating_density) + "&nbsp;kg/m<sup>3</sup>", c.coating_density_source);
  h << "</table>\n";
}

void verdictBlock(std::ostringstream& h, const RunAnalysis& a, const ReportOptions& o) {
  const auto& v = a.verdict;
  const auto t = verdictText(a, o);
  h << "<h2>Verdict</h2>\n<p class=\"verdict " << (v.well_mixed ? "ok" : "bad") << "\"><b>"
    << htmlEscape(t.head) << ":</b> " << htmlEscape(t.body) << "</p>\n";
  if (!v.relaxed.empty()) {
    h << "<p class=bad>Judged with non-default mixing criteria (cosim report --mixing):</p><ul>";
    for (const auto& r : v.relaxed) h << "<li>" << htmlEscape(r) << "</li>";
    h << "</ul>\n";
  }
}

void endOfRun(std::ostringstream& h, const RunAnalysis& a, const ReportOptions& o) {
  const auto& l = a.snapshots.back();
  const auto& mu = a.mass_unit;
  const bool thick = std::isfinite(a.conditions.grain.thickness(1.0));
  h << "<h2>Coating at the end of the run (t = " << htmlNumber(l.time)
    << "&nbsp;s)</h2>\n<table><tr><th class=l></th>"
    << "<th>per parcel " << unit(mu) << "</th><th>per real grain " << unit(mu) << "</th>";
  if (thick) h << "<th>as a layer on a grain " << unit(a.thickness_unit) << "</th>";
  h << "</tr>";
  auto line = [&](const char* name, double kg) {
    h << "<tr><td class=l>" << name << "</td><td>" << mass(a, kg) << "</td><td>" << perGrain(a, kg)
      << "</td>";
    if (thick) h << "<td>" << layer(a, kg) << "</td>";
    h << "</tr>";
  };
  line("mean", l.mean);
  line("standard deviation", l.std_dev);
  line("least coated", l.min);
  line("most coated", l.max);
  h << "</table>\n<table><tr><th class=l>quantity</th><th>value</th></tr>"
    << "<tr><td class=l>CV (standard deviation / mean)</td><td>" << htmlNumber(l.cv, 3)
    << "</td></tr>"
    << "<tr><td class=l>never coated (&le; " << htmlNumber(o.uncoated_relative, 2)
    << " &times; mean)</td><td>" << htmlPercent(l.uncoated_share, 1) << "</td></tr>"
    << "<tr><td class=l>coating on all " << l.count << " parcels</td><td>"
    << htmlQuantity(l.total, mu) << "</td></tr></table>\n";
  h << "<p>A parcel's coating is shared by the "
    << htmlNumber(std::pow(a.conditions.grain.cg, 3), 4) << " real grains it stands for";
  if (thick) h << "; the layer is that coating spread evenly over a real grain's surface";
  h << ". CV and shares are the same per parcel and per real grain.</p>\n";
  const auto& v = a.verdict;
  if (!v.reasons.empty()) {
    h << "<p>Why the run is judged poorly mixed (paper section 2.3):</p><ul>";
    for (const auto& r : v.reasons) h << "<li>" << htmlEscape(r) << "</li>";
    h << "</ul>\n";
  } else {
    h << "<p>Every mixing criterion passes: at most "
      << htmlPercent(o.criteria.max_uncoated_share, 0)
      << " never coated, mean and variance growing linearly with time (Eqs. 9-10), and a coating "
         "distribution "
         "close to normal (docs/analysis.md section 4).</p>\n";
  }
  if (!v.warnings.empty()) {
    h << "<p>Worth knowing:</p><ul>";
    for (const auto& w : v.warnings) h << "<li>" << htmlEscape(w) << "</li>";
    h << "</ul>\n";
  }
}

void extrapolation(std::ostringstream& h, const RunAnalysis& a, const ReportOptions& o) {
  h << "<h2>Extrapolation to a batch</h2>\n";
  if (!a.verdict.well_mixed) {
    h << "<p class=bad>None: the run is poorly mixed (see the verdict), so Eqs. 9-10 do not "
         "describe it and a "
         "long-time coating or CV from them would be wrong.</p>\n";
    return;
  }
  if (!a.fit.ok) {
    h << "<p class=bad>None: no fit (" << htmlEscape(a.fit.problem) << ").</p>\n";
    return;
  }
  const auto& mu = a.mass_unit;
  const bool thick = std::isfinite(a.conditions.grain.thickness(1.0));
  const std::string band = fmt::format("{:.0f}", 100 * o.band);
  h << "<p>Eqs. 9-10: mean a1 t, standard deviation a2 &radic;t, CV (a2/a1)/&radic;t, t counted "
       "from the "
       "coating start; the CV range is for an error of &plusmn;"
    << band
    << "&nbsp;% in a2 (paper Fig. 11).</p>\n<table><tr><th>coating time</th><th>mean per parcel "
    << unit(mu) << "</th><th>mean per real grain " << unit(mu) << "</th>";
  if (thick) h << "<th>layer " << unit(a.thickness_unit) << "</th>";
  h << "<th>standard deviation per parcel " << unit(mu)
    << "</th><th>CV</th><th>CV range (a2 &plusmn;" << band << "&nbsp;%)</th></tr>";
  std::vector<double> times = o.predict_times;
  times.push_back(o.predict_until);
  for (double t : times) {
    const auto d = predictDistribution(a.fit, t, o.band);
    h << "<tr><td>" << htmlDuration(t) << "</td><td>" << mass(a, d.mean) << "</td><td>"
      << perGrain(a, d.mean) << "</td>";
    if (thick) h << "<td>" << layer(a, d.mean) << "</td>";
    h << "<td>" << mass(a, d.sigma) << "</td><td>" << htmlNumber(d.cv, 3) << "</td><td>"
      << htmlNumber((1 - o.band) * d.cv, 3) << "&nbsp;&ndash;&nbsp;"
      << htmlNumber((1 + o.band) * d.cv, 3) << "</td></tr>";
  }
  h << "</table>\n";
  if (!a.prediction_check.points.empty()) {
    const auto& pc = a.prediction_check;
    h << "<p>Prediction checked against the " << pc.points.size()
      << " simulated snapshots after the fit window "
      << "(to t = " << htmlNumber(pc.points.back().time) << "&nbsp;s): largest error of the mean "
      << htmlPercent(pc.max_abs_mean_error) << ", of the standard deviation "
      << htmlPercent(pc.max_abs_std_error) << ", of the CV " << htmlPercent(pc.max_abs_cv_error)
      << " (all points in prediction_check.csv).</p>\n";
  } else {
    h << "<p>The run ends with the fit window: no later simulated time to check the prediction "
         "against "
         "(run longer than the window, or fit a shorter window, to get the check).</p>\n";
  }
}

void massBalanceSection(std::ostringstream& h, const RunAnalysis& a) {
  h << "<h2>Mass balance (paper Table 3)</h2>\n";
  if (!a.mass_balance) {
    h << "<p>" << htmlEscape(a.mass_balance_problem) << "</p>\n";
    return;
  }
  const auto& b = *a.mass_balance;
  auto line = [&](const std::string& name, double kg, int digits = 6) {
    h << "<tr><td class=l>" << name << "</td><td>" << mass(a, kg, digits) << "</td></tr>";
  };
  h << "<table><tr><th class=l>precursor</th><th>" << unit(a.mass_unit) << "</th></tr>";
  line("in", b.precursor_in);
  line("out", b.precursor_out);
  line("held in the gas (change)", b.held_change);
  line("expected coating (in &minus; out &minus; held change)", b.expected_coating);
  if (b.has_removed) line("removed from the gas by the coating sink", b.removed);
  line("coating on particles", b.obtained_coating);
  line("error (expected &minus; obtained)", b.error, 3);
  h << "<tr><td class=l>error %</td><td>" << htmlNumber(b.error_percent, 3)
    << "</td></tr></table>\n"
    << "<p>Initial state: " << htmlEscape(b.initial_state)
    << ". Coating on particles: " << htmlEscape(b.obtained_source) << ".</p>\n";
  if (b.has_removed && std::abs(b.pending) > 1e-9 * std::abs(b.removed)) {
    h << "<p class=note>" << htmlQuantity(b.pending, a.mass_unit, 3)
      << " removed from the gas is not on the particles (removed minus coating on particles). If "
         "the coating "
         "was read from timeseries.csv, the last step's credit comes after its last row; otherwise "
         "coating "
         "was lost between the fluid and the particles.</p>\n";
  }
}

// Error against run time: what each length of the fit window predicts, and at what cost
void windowStudyHtml(std::ostringstream& h, const RunAnalysis& a) {
  const auto& mu = a.mass_unit;
  if (!a.window_study.points.empty()) {
    const auto& w = a.window_study;
    const bool extrapolate = a.verdict.well_mixed;
    h << "<h3>Error against run time</h3>\n<p>The fit repeated on growing windows: how well each "
         "shorter window "
         "predicts the simulated CV at the end of the run (t = "
      << htmlNumber(w.run_end) << "&nbsp;s, CV = " << htmlNumber(w.simulated_cv_run_end, 3) << ")";
    if (extrapolate)
      h << " and how the CV extrapolated to " << htmlDuration(w.horizon) << " settles";
    h << ". Wall time is what the simulation needed to reach the end of the window.";
    if (!extrapolate)
      h << " The run is poorly mixed: no extrapolated CV; these numbers only show how the fit "
           "drifts.";
    h << "</p>\n<table><tr><th>window end [s]</th><th>wall time [s]</th><th>a1 [" << mu.name
      << "/s] &plusmn; HC3</th><th>a2 [" << mu.name << "/s<sup>0.5</sup>] &plusmn; HC3</th>";
    if (extrapolate) h << "<th>CV at " << htmlDuration(w.horizon) << "</th>";
    h << "<th>error of the predicted CV at the run end</th></tr>";
    for (const auto& p : w.points) {
      h << "<tr><td>" << htmlNumber(p.t_end) << "</td><td>" << htmlNumber(p.wall_seconds)
        << "</td>";
      if (p.ok) {
        h << "<td>" << mass(a, p.a1) << "&nbsp;&plusmn;&nbsp;" << mass(a, p.a1_se, 2) << "</td><td>"
          << mass(a, p.a2) << "&nbsp;&plusmn;&nbsp;" << mass(a, p.a2_se, 2) << "</td>";
        if (extrapolate) h << "<td>" << htmlNumber(p.cv_horizon, 3) << "</td>";
        h << "<td>" << htmlPercent(p.cv_run_end_error) << "</td>";
      } else {
        h << "<td colspan=" << (extrapolate ? 4 : 3) << " class=l>no fit (too few snapshots)</td>";
      }
      h << "</tr>";
    }
    h << "</table>\n";
  }
}

void statisticalDetail(std::ostringstream& h, const RunAnalysis& a) {
  const auto& mu = a.mass_unit;
  h << "<details><summary>Statistical detail: standard errors of the fit (particle bootstrap, "
       "HC3), "
       "normality (D'Agostino-Pearson), runs test, error against run time, every "
       "snapshot</summary>\n";
  h << "<h3>Fit of Eqs. 9-10 on [" << htmlNumber(a.fit.t0) << ", " << htmlNumber(a.fit.t1)
    << "]&nbsp;s</h3>\n";
  if (!a.fit.ok) {
    h << "<p class=bad>No fit: " << htmlEscape(a.fit.problem) << "</p>\n";
  } else {
    const double nan = std::nan("");
    auto se = [&](double v) { return mass(a, v, 3); };
    h << "<table><tr><th class=l>parameter</th><th>value</th><th>standard error (particle "
         "bootstrap)</th>"
         "<th>standard error (regression, HC3)</th><th>standard error (regression, "
         "classic)</th></tr>"
      << "<tr><td class=l>a1 [" << mu.name << "/s]</td><td>" << mass(a, a.fit.a1) << "</td><td>"
      << se(a.bootstrap.ok ? a.bootstrap.a1_se : nan) << "</td><td>" << se(a.fit.a1_se)
      << "</td><td>" << se(a.fit.a1_se_classic) << "</td></tr><tr><td class=l>a2 [" << mu.name
      << "/s<sup>0.5</sup>]</td><td>" << mass(a, a.fit.a2) << "</td><td>"
      << se(a.bootstrap.ok ? a.bootstrap.a2_se : nan) << "</td><td>" << se(a.fit.a2_se)
      << "</td><td>" << se(a.fit.a2_se_classic) << "</td></tr></table>\n<p>";
    if (a.bootstrap.ok) {
      h << "Bootstrap: " << a.bootstrap.resamples << " resamples of the " << a.bootstrap.parcels
        << " parcels over " << a.bootstrap.snapshots
        << " snapshots of the window; it accounts for the "
        << "snapshots following the same parcels, which the regression errors ignore (they are too "
           "small for "
           "such data). ";
    } else if (!a.bootstrap.problem.empty()) {
      h << "No bootstrap: " << htmlEscape(a.bootstrap.problem) << ". ";
    }
    h << a.fit.tau.size() << " snapshots; RMS residual " << htmlPercent(a.fit.mean_relative_rms)
      << " of the mean (mean fit), " << htmlPercent(a.fit.variance_relative_rms)
      << " of the mean variance (variance fit).</p>\n";
  }
  const auto& v = a.verdict;
  h << "<h3>Normality of the last snapshot in the window</h3>\n<p>";
  if (v.normality.valid) {
    h << "D'Agostino-Pearson on " << v.normality.n << " parcels: skewness "
      << htmlNumber(v.normality.skewness, 3) << ", excess kurtosis "
      << htmlNumber(v.normality.kurtosis - 3.0, 3)
      << ", K<sup>2</sup> = " << htmlNumber(v.normality.k2)
      << ", p = " << htmlNumber(v.normality.p_value, 3) << ".";
    const auto& tr = v.trend;
    if (tr.measured) {
      h << " Over the last three quarters of the coating time (" << htmlNumber(tr.from, 3)
        << "&ndash;" << htmlNumber(tr.to, 3) << " s of coating, " << tr.snapshots
        << " snapshots) |skewness| falls as t<sup>&minus;" << htmlNumber(tr.skewness_decay, 3)
        << "</sup> and |excess kurtosis| as t<sup>&minus;" << htmlNumber(tr.kurtosis_decay, 3)
        << "</sup> (a well-mixed bed: t<sup>&minus;1/2</sup> and t<sup>&minus;1</sup>, every "
           "cumulant of the coating growing linearly in time)";
      if (std::isfinite(tr.at)) {
        h << "; projected to " << htmlNumber(tr.at, 3) << " s: skewness "
          << htmlNumber(tr.projected_skewness, 3) << ", excess kurtosis "
          << htmlNumber(tr.projected_excess_kurtosis, 3);
      }
      h << (v.fading_non_normal ? ": the departure fades, so it does not refuse the run." : ".");
    }
  } else {
    h << htmlEscape(v.normality.problem);
  }
  h << "</p>\n<h3>Runs test on the signs of the residuals</h3>\n<table><tr><th "
       "class=l>fit</th><th>runs</th>"
       "<th>expected</th><th>p (too few runs)</th></tr>";
  for (const auto& [name, r] :
       {std::pair<const char*, const RunsTest&>{"mean", v.mean_runs},
        std::pair<const char*, const RunsTest&>{"variance", v.variance_runs}}) {
    h << "<tr><td class=l>" << name << "</td>";
    if (r.valid) {
      h << "<td>" << r.runs << "</td><td>" << htmlNumber(r.expected_runs, 3) << "</td><td>"
        << htmlNumber(r.p_too_few, 3) << "</td>";
    } else {
      h << "<td colspan=3>&ndash;</td>";
    }
    h << "</tr>";
  }
  h << "</table>\n";

  windowStudyHtml(h, a);

  h << "<h3>Statistics over time</h3>\n<table><tr><th>t [s]</th><th>parcels</th><th>mean per "
       "parcel "
    << unit(mu) << "</th><th>standard deviation " << unit(mu)
    << "</th><th>CV</th><th>never coated</th></tr>";
  const std::size_t n = a.snapshots.size();
  const std::size_t stride = n > 25 ? (n + 24) / 25 : 1;
  for (std::size_t i = 0; i < n; i += stride) {
    const auto& s = a.snapshots[i];
    h << "<tr><td>" << htmlNumber(s.time) << "</td><td>" << s.count << "</td><td>"
      << mass(a, s.mean) << "</td><td>" << mass(a, s.std_dev) << "</td><td>" << htmlNumber(s.cv, 3)
      << "</td><td>" << htmlPercent(s.uncoated_share) << "</td></tr>";
  }
  h << "</table>\n<p>Every snapshot: statistics.csv (SI units).</p>\n</details>\n";
}
}  // namespace

void writeRunHtml(const RunAnalysis& a, const ReportOptions& o, const std::filesystem::path& dir,
                  const std::vector<std::string>& pngs, const std::string& plot_message) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cosim report: "
    << htmlEscape(a.label) << "</title>\n"
    << kStyle << "</head><body>\n<h1>Coating report: " << htmlEscape(a.label) << "</h1>\n"
    << "<p>Run folder: <code>" << htmlEscape(a.run.string()) << "</code>. " << a.snapshots.size()
    << " snapshots from t = " << htmlNumber(a.snapshots.front().time) << " s to "
    << htmlNumber(a.snapshots.back().time) << " s. Coating masses in " << a.mass_unit.name
    << " throughout this page (report.json and the CSV "
    << "tables in this folder keep SI units).</p>\n";
  if (!plot_message.empty())
    h << "<p class=\"note\">Plots missing: " << htmlEscape(plot_message) << "</p>\n";
  if (!a.run_status.empty() && a.run_status != "completed") {
    h << "<p class=\"note\">The run did not complete (summary.json status: "
      << htmlEscape(a.run_status)
      << "): this report covers what it recorded up to t = " << htmlNumber(a.snapshots.back().time)
      << " s.</p>\n";
  }
  conditionsTable(h, a);
  verdictBlock(h, a, o);
  endOfRun(h, a, o);
  extrapolation(h, a, o);
  h << zonePassesHtml(a);
  h << batchHtml(a);
  massBalanceSection(h, a);
  if (std::isfinite(a.wall_seconds)) {
    h << "<p>Run time: " << htmlNumber(a.wall_seconds) << " s wall clock over " << a.steps
      << " coupling steps ("
      << htmlNumber(a.wall_seconds / static_cast<double>(a.steps > 0 ? a.steps : 1))
      << " s per step).</p>\n";
  }
  h << "<h2>Figures</h2>\n";
  figures(h, pngs, kRunFigures, std::size(kRunFigures), !a.verdict.well_mixed);
  statisticalDetail(h, a);
  h << "</body></html>\n";
  writeFileAtomically(dir / "report.html", h.str());
}

namespace {
const Figure kComparisonFigures[] = {
    {"compare_side_by_side.png",
     "The runs side by side, one column each with its verdict: CV over time, CV against mean "
     "coating (paper "
     "Fig. 8), and the growth of the mean and of the standard deviation with the fit of Eqs. 9-10 "
     "(paper "
     "Fig. 10)."},
    {"compare_cv_mean.png", "CV against mean coated mass for every run (paper Fig. 8)."},
    {"compare_statistics_time.png", "Mean coating mass and CV over time for every run."},
    {"compare_histograms.png", "Coating histograms at the end of every run (paper Fig. 6)."},
};

// Operating conditions a comparison shows in their own columns (not again as varied parameters).
bool shownAsCondition(const std::string& name) {
  if (name == kFlowParameter || name == kMinimumFluidizationParameter ||
      name == kNozzleVelocityParameter || name == kPrecursorFractionParameter) {
    return true;
  }
  for (const char* n : kSuperficialVelocityParameters) {
    if (name == n) return true;
  }
  return false;
}
}  // namespace

void writeComparisonHtml(const std::vector<RunAnalysis>& runs,
                         const std::vector<std::string>& folders, const ReportOptions& o,
                         const std::filesystem::path& dir, const std::vector<std::string>& pngs,
                         const std::string& plot_message) {
  const auto& mu = runs.front().mass_unit;
  const auto& tu = runs.front().thickness_unit;
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cosim comparison "
       "report</title>\n"
    << kStyle << "</head><body>\n<h1>Coating comparison of " << runs.size()
    << " runs</h1>\n<p>Coating masses in " << mu.name
    << " throughout this page; every run's own report: follow its link. Numbers: comparison.json, "
    << "comparison.csv (SI units).</p>\n";
  if (!plot_message.empty())
    h << "<p class=\"note\">Plots missing: " << htmlEscape(plot_message) << "</p>\n";
  std::vector<std::string> varied;
  for (const auto& n : variedParameters(runs)) {
    if (!shownAsCondition(n)) varied.push_back(n);
  }
  auto link = [&](std::size_t i) {
    return "<a href=\"" + htmlEscape(folders[i]) + "/report.html\">" + htmlEscape(runs[i].label) +
           "</a>";
  };

  h << "<h2>Operating conditions and verdicts</h2>\n<table><tr><th class=l>run</th>";
  for (const auto& n : varied) h << "<th>" << htmlEscape(n) << "</th>";
  h << "<th>flow [L/min]</th><th>u [m/s]</th><th>u / u<sub>mf</sub></th><th>coating "
       "time</th><th>parcels</th>"
       "<th class=l>verdict</th></tr>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& a = runs[i];
    const auto& c = a.conditions;
    h << "<tr><td class=l>" << link(i) << "</td>";
    for (const auto& n : varied) h << "<td>" << htmlNumber(parameter(a, n), 6) << "</td>";
    h << "<td>" << htmlNumber(c.flow_lpm) << "</td><td>" << htmlNumber(c.superficial_velocity, 3)
      << "</td><td>" << htmlNumber(c.uOverUmf(), 3) << "</td><td>" << htmlDuration(c.coating_time)
      << "</td><td>" << c.parcels << "</td><td class=l>";
    const auto t = verdictText(a, o);
    h << "<span class=" << (a.verdict.well_mixed ? "ok" : "bad") << ">" << htmlEscape(t.head)
      << ":</span> " << htmlEscape(t.body) << "</td></tr>\n";
  }
  h << "</table>\n";
  if (std::isfinite(runs.front().conditions.u_mf)) {
    h << "<p>u<sub>mf</sub>: " << htmlEscape(runs.front().conditions.u_mf_source) << ".</p>\n";
  }

  const auto t = batchTimes(o);
  const bool thick = std::isfinite(runs.front().conditions.grain.thickness(1.0));
  h << "<h2>Coating side by side</h2>\n<table><tr><th class=l>run</th><th>mean per parcel "
    << unit(mu) << "</th><th>mean per real grain " << unit(mu) << "</th>";
  if (thick) h << "<th>layer " << unit(tu) << "</th>";
  h << "<th>CV</th><th>never coated</th><th>never in the zone</th><th>mean cycle</th>";
  for (double x : t) h << "<th>CV at " << htmlDuration(x) << " (well mixed only)</th>";
  h << "</tr>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& a = runs[i];
    const auto& l = a.snapshots.back();
    h << "<tr><td class=l>" << link(i) << "</td><td>" << mass(a, l.mean) << "</td><td>"
      << perGrain(a, l.mean) << "</td>";
    if (thick) h << "<td>" << layer(a, l.mean) << "</td>";
    h << "<td>" << htmlNumber(l.cv, 3) << "</td><td>" << htmlPercent(l.uncoated_share, 1)
      << "</td><td>"
      << (a.zone_passes ? htmlPercent(a.zone_passes->stats.never_entered_share, 1) : "&ndash;")
      << "</td><td>"
      << (a.zone_passes ? htmlDuration(a.zone_passes->stats.cycle_time.mean) : "&ndash;")
      << "</td>";
    if (a.verdict.well_mixed && a.fit.ok) {
      for (double x : t)
        h << "<td>" << htmlNumber(predictDistribution(a.fit, x, o.band).cv, 3) << "</td>";
    } else {
      h << "<td colspan=" << t.size() << " class=l>"
        << (a.verdict.well_mixed ? "no fit" : "refused: poorly mixed") << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</table>\n<p>Mean, CV and shares at the end of each run; the CV of a batch is extrapolated "
       "with Eqs. 9-10 "
       "for well-mixed runs only.</p>\n";
  figures(h, pngs, kComparisonFigures, std::size(kComparisonFigures));

  h << "<details><summary>Fit, mass balance and run time of every run</summary>\n<table><tr><th "
       "class=l>run</th>"
    << "<th>end [s]</th><th>coating on all parcels " << unit(mu) << "</th><th>a1 [" << mu.name
    << "/s]</th><th>a2 [" << mu.name
    << "/s<sup>0.5</sup>]</th><th>mass balance error %</th><th>wall time [s]</th>"
    << "<th class=l>mixing criteria</th></tr>\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& a = runs[i];
    const auto& l = a.snapshots.back();
    h << "<tr><td class=l>" << link(i) << "</td><td>" << htmlNumber(l.time) << "</td><td>"
      << mass(a, l.total) << "</td><td>"
      << (a.fit.ok ? mass(a, a.fit.a1) + "&nbsp;&plusmn;&nbsp;" + mass(a, a.a1Error(), 2)
                   : "&ndash;")
      << "</td><td>"
      << (a.fit.ok ? mass(a, a.fit.a2) + "&nbsp;&plusmn;&nbsp;" + mass(a, a.a2Error(), 2)
                   : "&ndash;")
      << "</td><td>" << (a.mass_balance ? htmlNumber(a.mass_balance->error_percent, 3) : "&ndash;")
      << "</td><td>" << htmlNumber(a.wall_seconds) << "</td><td class=l>";
    if (a.verdict.reasons.empty()) h << "all pass";
    for (std::size_t k = 0; k < a.verdict.reasons.size(); ++k) {
      h << (k ? "<br>" : "") << htmlEscape(a.verdict.reasons[k]);
    }
    h << "</td></tr>\n";
  }
  h << "</table>\n<p>a1 and a2 &plusmn; their particle-bootstrap standard error (HC3 when there is "
       "no "
       "bootstrap).</p>\n</details>\n</body></html>\n";
  writeFileAtomically(dir / "comparison.html", h.str());
}

}  // namespace cosim::analysis
