// runReport: the `cosim report RUN [RUN...]` command.
#include "cosim/analysis/report.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <set>
#include <stdexcept>

#include "cosim/analysis/bed_report.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/summary.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
void removePngs(const std::filesystem::path& dir) {
  for (const auto& p : pngsIn(dir)) std::filesystem::remove(dir / p);
}

void prepare(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw Error(ec ? kindOfErrno(ec.value()) : ErrorKind::input,
                "cannot create the report folder " + dir.string() + ": " + ec.message() +
                    " (choose another with --output)");
  }
  removePngs(dir);  // a figure left from an earlier report must not pass for a new one
}
void validate(const ReportOptions& o) {
  auto bad = [](const std::string& option, double value, const std::string& expected) {
    throw InputError("report option " + option + " = " + std::to_string(value) + ": expected " +
                     expected);
  };
  if (!std::isfinite(o.coating_start)) bad("--coating-start", o.coating_start, "a time in seconds");
  for (double t : o.predict_times) {
    if (!(t > 0)) bad("--predict", t, "times after the coating start, in seconds (e.g. 300,1200)");
  }
  for (double t : o.histogram_times) {
    if (!std::isfinite(t)) bad("--histograms", t, "times in seconds");
  }
  if (!(o.predict_until > 0))
    bad("predict_until", o.predict_until, "a positive horizon in seconds (3600 = 60 min)");
  if (!(o.band >= 0 && o.band < 1))
    bad("band", o.band, "a relative error of a2 between 0 and 1 (0.2 = 20 %)");
  if (!std::isnan(o.coating_density) && !(o.coating_density > 0)) {
    bad("--coating-density", o.coating_density,
        "the density of the coating layer in kg/m3 (e.g. 1500)");
  }
  if (!std::isnan(o.u_mf) && !(o.u_mf > 0)) {
    bad("--u-mf", o.u_mf, "the minimum fluidization velocity in m/s (e.g. 0.075)");
  }
  if (!(o.uncoated_relative >= 0))
    bad("uncoated_relative", o.uncoated_relative, "a fraction of the mean >= 0 (1e-6)");
  if (!std::isnan(o.fit_start) && !std::isnan(o.fit_end) && !(o.fit_end > o.fit_start)) {
    throw InputError("report options --fit-start " + std::to_string(o.fit_start) +
                     " and --fit-end " + std::to_string(o.fit_end) +
                     ": the window is empty; give --fit-end after --fit-start");
  }
}
}  // namespace

std::vector<std::string> writeRunReport(const RunAnalysis& a, const ReportOptions& o,
                                        const std::filesystem::path& dir,
                                        std::string& plot_message) {
  prepare(dir);
  writeJsonFile(dir / "report.json", toJson(a, o), 1);
  writeRunTables(a, dir);
  plot_message.clear();
  if (o.plots)
    drawPlots(dir, plot_message);
  else
    plot_message = "plots switched off (--no-plots)";
  const auto pngs = pngsIn(dir);
  writeRunHtml(a, o, dir, pngs, plot_message);
  return pngs;
}

std::vector<std::string> variedParameters(const std::vector<RunAnalysis>& runs) {
  std::vector<std::string> names;
  if (runs.size() < 2) return names;
  for (const auto& [name, value] : runs.front().parameters) {
    bool differs = false, everywhere = true;
    for (const auto& r : runs) {
      bool found = false;
      for (const auto& [n, v] : r.parameters) {
        if (n == name) {
          found = true;
          differs = differs || v != value;
        }
      }
      everywhere = everywhere && found;
    }
    if (differs && everywhere) names.push_back(name);
  }
  return names;
}

double parameter(const RunAnalysis& a, const std::string& name) {
  for (const auto& [n, v] : a.parameters) {
    if (n == name) return v;
  }
  return std::nan("");
}

namespace {
// One run's line of the comparison: its end, fit, verdict, batch CVs and zone passes
Json comparedRunJson(const RunAnalysis& a, const std::string& folder,
                     const std::vector<std::string>& varied, const ReportOptions& o) {
  const auto& l = a.snapshots.back();
  std::string legend = a.label;
  Json parameters = Json::object();
  for (const auto& n : varied) {
    parameters[n] = parameter(a, n);
    // 4 significant digits: a legend, not a record (parameters keep full precision)
    legend += fmt::format(" {}={:.4g}", n, parameter(a, n));
  }
  Json cv_batch = Json::array();  // at batch_times_s; null for a poorly mixed run (refused)
  for (double t : batchTimes(o)) {
    cv_batch.push_back(
        a.verdict.well_mixed && a.fit.ok ? Json(predictDistribution(a.fit, t, o.band).cv) : Json());
  }
  const double nan = std::nan("");
  const auto* zp = a.zone_passes ? &a.zone_passes->stats : nullptr;
  return {{"label", a.label},
          {"parameters", parameters},
          {"legend", legend},
          {"run", a.run.string()},
          {"report", folder + "/report.json"},
          {"end_time", l.time},
          {"total", l.total},
          {"mean", l.mean},
          {"cv", l.cv},
          {"uncoated_share", l.uncoated_share},
          {"fit_ok", a.fit.ok},
          {"a1", a.fit.a1},
          {"a1_se", a.a1Error()},
          {"a2", a.fit.a2},
          {"a2_se", a.a2Error()},
          {"well_mixed", a.verdict.well_mixed},
          {"verdict", a.verdict.summary()},
          {"verdict_short", shortVerdict(a.verdict)},
          {"verdict_plain", plainVerdict(a, o)},
          {"conditions", conditionsJson(a.conditions)},
          {"mean_per_grain", a.conditions.grain.perGrain(l.mean)},
          {"layer_thickness_m", a.conditions.grain.thickness(l.mean)},
          {"cv_batch", cv_batch},
          {"mass_balance_error_percent", a.mass_balance ? a.mass_balance->error_percent : nan},
          {"wall_seconds", a.wall_seconds},
          {"never_in_zone_share", zp ? zp->never_entered_share : nan},
          {"cycle_time_s", zp ? zp->cycle_time.mean : nan},
          {"cycle_time_from_rate_s", zp ? zp->cycle_time_from_rate : nan},
          {"pass_duration_s", zp ? zp->pass_duration.mean : nan}};
}
}  // namespace

Json comparisonJson(const std::vector<RunAnalysis>& runs, const std::vector<std::string>& folders,
                    const ReportOptions& o) {
  const auto varied = variedParameters(runs);
  Json compared = Json::array();
  for (std::size_t i = 0; i < runs.size(); ++i)
    compared.push_back(comparedRunJson(runs[i], folders[i], varied, o));
  return {{"format", "cosim-comparison"},
          {"version", 1},
          {"units", unitsJson(runs.front())},  // the same for every run of a comparison
          {"batch_times_s", batchTimes(o)},
          {"varied_parameters", varied},
          {"runs", compared}};
}

void writeComparisonTables(const std::vector<RunAnalysis>& runs, const std::filesystem::path& dir) {
  std::string csv =
      "run,end_time_s,total_kg,mean_kg,cv,uncoated_share,a1_kg_per_s,a1_se,a2_kg_per_sqrt_s,a2_se,"
      "well_mixed,"
      "mass_balance_error_percent,wall_seconds,flow_lpm,u_m_per_s,u_over_umf,mean_per_grain_kg,"
      "layer_thickness_m\n";
  for (const auto& a : runs) {
    const auto& l = a.snapshots.back();
    csv += fmt::format(
        "\"{}\",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{:.10g},"
        "{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n",
        a.label, l.time, l.total, l.mean, l.cv, l.uncoated_share, a.fit.a1, a.a1Error(), a.fit.a2,
        a.a2Error(), a.verdict.well_mixed ? 1 : 0,
        a.mass_balance ? a.mass_balance->error_percent : std::nan(""), a.wall_seconds,
        a.conditions.flow_lpm, a.conditions.superficial_velocity, a.conditions.uOverUmf(),
        a.conditions.grain.perGrain(l.mean), a.conditions.grain.thickness(l.mean));
  }
  writeFileAtomically(dir / "comparison.csv", csv);
}

namespace {
// Whether the run's records hold coating: its particles.h5's fields, else its summary.json's
// word; a run with neither is left to the coating analysis, which says what is missing.
bool hasCoating(const std::filesystem::path& run) {
  if (std::filesystem::exists(run / kParticlesFile))
    return ParticleFile(run / kParticlesFile).hasField(cosim::field::coating_mass);
  if (std::filesystem::exists(run / kSummaryFile)) return readSummary(run / kSummaryFile).coating;
  return true;
}

// One run without coating: the bed over the window (the second half of the record unless
// --fit-start / --fit-end say otherwise), as report.json and report.md.
int runBedReport(const ReportOptions& o, std::ostream& log) {
  const auto& run = o.runs.front();
  log << "cosim report: analysing " << run.string() << " (no coating: the bed's own records)\n";
  const BedAnalysis a = analyseBed(run, o.fit_start, o.fit_end);
  const std::filesystem::path out = o.output.empty() ? run / "report" : o.output;
  claimOutputFolder(out, "report.json", "\"cosim-report\"", "cosim report -o");
  prepare(out);
  writeJsonFile(out / "report.json", toJson(a), 1);
  writeFileAtomically(out / "report.md", bedReportText(a));
  log << fmt::format("cosim report: {}: over t = {:g} .. {:g} s", a.label, a.from, a.to);
  if (a.pressure_drop.n > 0)
    log << fmt::format(", pressure drop {:.4g} Pa (+- {:.3g})", a.pressure_drop.mean,
                       a.pressure_drop.sd);
  if (a.height_median.n > 0)
    log << fmt::format(", median parcel height {:.4g} mm", 1000 * a.height_median.mean);
  log << "\ncosim report: wrote " << (out / "report.md").string() << " and report.json\n";
  return 0;
}
}  // namespace

int runReport(const ReportOptions& o) {
  std::ostream& log = o.log != nullptr ? *o.log : std::cout;
  try {
    if (o.runs.empty()) throw InputError("no run folder given: `cosim report RUN [RUN...]`");
    validate(o);
    if (!hasCoating(o.runs.front()) && o.runs.size() == 1) return runBedReport(o, log);
    for (const auto& run : o.runs)
      if (!hasCoating(run))
        throw InputError(run.string() +
                         " has no coating (no coating_mass in its particles.h5): a comparison "
                         "compares coating; report it alone (`cosim report " +
                         run.string() + "`) for what its bed did");
    std::vector<RunAnalysis> analyses;
    for (const auto& run : o.runs) {
      log << "cosim report: analysing " << run.string() << "\n";
      analyses.push_back(analyseRun(run, o));
    }
    chooseDisplayUnits(analyses);  // one unit for every run of a comparison
    const bool several = o.runs.size() > 1;
    std::filesystem::path out = o.output;
    if (out.empty()) {
      out = several ? o.runs.front().lexically_normal().parent_path() / "report-comparison"
                    : o.runs.front() / "report";
    }
    std::vector<std::string> folders;
    std::set<std::string> used;
    for (const auto& a : analyses) {
      std::string folder = a.label.empty() ? "run" : a.label;
      for (int k = 2; used.count(folder) != 0; ++k) folder = a.label + "-" + std::to_string(k);
      used.insert(folder);
      folders.push_back(folder);
    }
    // A report replaces the figures of its folder: only a new or empty folder, or one an earlier
    // report wrote, is written into; every folder is checked before anything is written.
    if (several) {
      claimOutputFolder(out, "comparison.json", "\"cosim-comparison\"", "cosim report -o");
      for (const auto& folder : folders)
        claimOutputFolder(out / folder, "report.json", "\"cosim-report\"", "cosim report -o");
    } else {
      claimOutputFolder(out, "report.json", "\"cosim-report\"", "cosim report -o");
    }
    std::string anyPlotProblem;
    for (std::size_t i = 0; i < analyses.size(); ++i) {
      const auto& a = analyses[i];
      const auto dir = several ? out / folders[i] : out;
      std::string plotMessage;
      const auto pngs = writeRunReport(a, o, dir, plotMessage);
      log << "cosim report: " << a.label << ": " << a.verdict.summary() << "\n";
      if (a.mass_balance) {
        log << fmt::format("cosim report: {}: mass balance error {:.3g} kg ({:.3g} %)\n", a.label,
                           a.mass_balance->error, a.mass_balance->error_percent);
      }
      log << "cosim report: wrote " << (dir / "report.html").string() << " (" << pngs.size()
          << " figures)\n";
      if (!plotMessage.empty()) anyPlotProblem = plotMessage;
    }
    if (several) {
      prepare(out);
      writeJsonFile(out / "comparison.json", comparisonJson(analyses, folders, o), 1);
      writeComparisonTables(analyses, out);
      std::string plotMessage;
      if (o.plots)
        drawPlots(out, plotMessage);
      else
        plotMessage = "plots switched off (--no-plots)";
      const auto pngs = pngsIn(out);
      writeComparisonHtml(analyses, folders, o, out, pngs, plotMessage);
      log << "cosim report: wrote " << (out / "comparison.html").string() << " (" << pngs.size()
          << " figures)\n";
      if (!plotMessage.empty()) anyPlotProblem = plotMessage;
    }
    if (!anyPlotProblem.empty() && o.plots) {
      log << "cosim report: numbers and HTML tables written, but no plots: " << anyPlotProblem
          << "\n";
    }
    int rc = 0;
    if (!std::isnan(o.mass_balance_limit_percent)) {
      for (const auto& a : analyses) {
        if (!a.mass_balance) {
          std::cerr << "cosim report: " << a.label
                    << ": mass balance check failed: " << a.mass_balance_problem << "\n";
          rc = 3;
        } else if (!(std::abs(a.mass_balance->error_percent) <= o.mass_balance_limit_percent)) {
          std::cerr << fmt::format(
              "cosim report: {}: mass balance error {:.3g} % exceeds the limit {:.3g} %\n", a.label,
              a.mass_balance->error_percent, o.mass_balance_limit_percent);
          rc = 3;
        } else {
          log << "cosim report: " << a.label << ": mass balance within "
              << o.mass_balance_limit_percent << " %\n";
        }
      }
    }
    return rc;
  } catch (const std::exception& e) {
    std::cerr << "cosim report: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace cosim::analysis
