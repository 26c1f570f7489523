// cosim report RUN [RUN...] [options]: coating statistics, fits, extrapolation, the whole batch,
// plots, HTML
#include "cosim/analysis/report.h"

#include <charconv>
#include <cstring>
#include <memory>
#include <optional>

#include "commands.h"

namespace cosim::orchestrator {

namespace {

namespace a = cosim::analysis;

// --mixing NAME=VALUE: the criterion and its value, or nullopt when the text is not one
std::optional<std::pair<const a::MixingCriterion*, double>> mixingOverride(const std::string& m) {
  const auto eq = m.find('=');
  if (eq == std::string::npos) return std::nullopt;
  for (const auto& k : a::kMixingCriteria) {
    if (m.compare(0, eq, k.name) != 0 || eq != std::strlen(k.name)) continue;
    double value = 0;
    const char* end = m.data() + m.size();
    const auto [ptr, ec] = std::from_chars(m.data() + eq + 1, end, value);
    if (ec != std::errc() || ptr != end || !(value >= 0)) return std::nullopt;
    return std::make_pair(&k, value);
  }
  return std::nullopt;
}

std::string criterionNames() {
  std::string names;
  for (const auto& k : a::kMixingCriteria)
    names += (names.empty() ? "" : ", ") + std::string(k.name);
  return names;
}

}  // namespace

void addReportCommand(CLI::App& app, Commands& commands) {
  struct Options {
    a::ReportOptions report;
    std::vector<std::string> mixing;
  };
  auto o = std::make_shared<Options>();
  auto& r = o->report;
  auto* rep = app.add_subcommand(
      "report", "Analyse run folders: coating statistics, fits, extrapolation, plots, HTML");
  rep->add_option("runs", r.runs, "run folders (several: one comparison report, e.g. a flow sweep)")
      ->required();
  rep->add_option("-o,--output", r.output,
                  "report folder (default: RUN/report for one run, report-comparison beside the "
                  "runs for several)");
  rep->add_option("--fit-start", r.fit_start,
                  "start of the fit window [s] (default: first snapshot)");
  rep->add_option("--fit-end", r.fit_end, "end of the fit window [s] (default: last snapshot)");
  rep->add_option("--coating-start", r.coating_start,
                  "time coating starts [s], origin of mu = a1 t");
  rep->add_option("--histograms", r.histogram_times, "times of the histograms [s]")->delimiter(',');
  rep->add_option("--predict", r.predict_times, "times of the extrapolated distributions [s]")
      ->delimiter(',');
  rep->add_option("--predict-until", r.predict_until,
                  "horizon of the CV prediction [s] (default 3600)");
  rep->add_option("--band", r.band,
                  "relative band on a2 drawn around the CV prediction (default 0.2)");
  rep->add_option(
      "--bootstrap", r.bootstrap_resamples,
      "particle-bootstrap resamples for the errors of a1, a2 (default 100; 0 = HC3 errors only)");
  rep->add_option(
      "--uncoated-threshold", r.uncoated_relative,
      "a particle counts as never coated below this fraction of the mean coating (default 1e-6)");
  rep->add_option("--coating-density", r.coating_density,
                  "density of the coating layer [kg/m3] for its thickness (default: the scene's "
                  "parameter coating_density, else 1500)");
  rep->add_option("--u-mf", r.u_mf,
                  "minimum fluidization velocity [m/s] for u/u_mf (default: the scene's parameter "
                  "u_mf, else Wen-Yu for the real grains)");
  rep->add_option("--check-mass-balance", r.mass_balance_limit_percent,
                  "exit 3 if a run's mass-balance error exceeds this many percent (e.g. 0.01)");
  rep->add_option(
         "--mixing", o->mixing,
         "override a mixing criterion, NAME=VALUE (names in docs/analysis.md, e.g. "
         "max_uncoated_share=0.3); the report then says it was judged with non-default criteria")
      ->check(CLI::Validator(
          [](std::string& m) {
            return mixingOverride(m)
                       ? std::string()
                       : "expected NAME=VALUE with VALUE >= 0 and NAME one of " + criterionNames();
          },
          "NAME=VALUE"));
  rep->add_flag("--no-plots{false}", r.plots, "numbers and HTML only, no matplotlib");
  rep->add_flag("--no-batch{false}", r.batch,
                "leave out the whole batch by the long-time model (cosim batch)");
  commands.push_back({rep, [o] {
                        for (const auto& m : o->mixing) {
                          const auto [criterion, value] = *mixingOverride(m);
                          o->report.criteria.*criterion->value = value;
                        }
                        return a::runReport(o->report);
                      }});
}

}  // namespace cosim::orchestrator
