// cosim: the orchestrator's command line.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "adapter_check.h"
#include "bench.h"
#include "cosim/models/drag/undisturbed_velocity.h"
#include "cosim/models/registry.h"
#include "coupler.h"
#include "batch_command.h"
#include "ft4_command.h"
#include "keys_command.h"
#include "launchers.h"
#include "link_security.h"
#include "plan.h"
#include "run_pack.h"
#include "scenario.h"
#include "cosim/util/long_quotes.h"
#include "study.h"

#if __has_include("cosim/analysis/report.h")
#include "cosim/analysis/piv_command.h"
#include "cosim/analysis/report.h"
#define COSIM_HAVE_REPORT 1
#endif

using namespace cosim::orchestrator;

namespace {

void onSignal(int sig) {
  g_stop_signal = sig;
  ++g_stop_count;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none)" : s;
}

int validate(const std::string& file, const std::vector<std::string>& sets,
             const std::vector<std::string>& unsets) {
  Scenario sc = loadScenario(file, sets, unsets);
  SceneModels m = makeModels(sc);
  Plan p = makePlan(sc, m);
  const auto checked = checkAdapters(sc, p);  // the adapters' own view of the scene
  std::cout << "scenario '" << sc.name << "' is valid (" << sc.file.string() << ")\n";
  std::cout << "  coupling: dt " << sc.coupling.dt << " s x " << sc.coupling.dem_steps
            << " DEM steps, t = " << sc.coupling.start_time << " .. " << sc.coupling.end_time
            << " s ("
            << static_cast<long long>(
                   std::llround((sc.coupling.end_time - sc.coupling.start_time) / sc.coupling.dt))
            << " steps), scheme " << sc.coupling.scheme << "\n";
  std::cout << "  particles: " << sc.participants.at("particles").adapter << "; sends "
            << join(p.particles_send) << "; receives " << join(p.particles_receive) << "\n";
  if (p.fluid) {
    std::cout << "  fluid: " << sc.participants.at("fluid").adapter << "; sends "
              << join(p.fluid_send) << "; receives " << join(p.fluid_receive) << "\n";
  }
  std::cout << "  models: drag " << (sc.models.drag ? sc.models.drag->law : "none") << ", forces "
            << sc.models.forces.size() << ", mass transfer "
            << (sc.models.mass_transfer ? sc.models.mass_transfer->law : "none")
            << ", coating zone " << (sc.models.coating_zone ? sc.models.coating_zone->law : "none")
            << "\n";
  std::cout << "  link: " << linkDescription(sc.transport) << "\n";
  for (const auto& [name, spec] : sc.participants) {
    if (name == "fluid" && !p.fluid) continue;
    const bool curve = isTcp(sc.transport.bind) && !sc.transport.insecure;
    std::cout << "  launch " << name << ": " << describeLaunch(spec)
              << (!curve ? ""
                  : spec.launch != "external"
                      ? "; its run keys through the environment"
                      : "; its run keys in RUN/.cosim-" + name + ".key (--key-file)")
              << "\n";
  }
  for (const auto& v : sc.shown)
    std::cout << "  shows: " << v.name << " = " << fmt::format("{:.6g}", v.value)
              << (v.doc.empty() ? "" : "  (" + v.doc + ")") << "\n";
  for (const auto& n : p.notes) std::cout << "  note: " << n << "\n";
  for (const auto& a : checked) std::cout << "  checked: " << a << "\n";
  std::cout << "  output: " << sc.output.folder.string() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "cosim: CFD-DEM co-simulation orchestrator.\n"
      "Runs OpenFOAM and LIGGGHTS (or the analytic adapters) as separate processes coupled over\n"
      "ZeroMQ, with drag, mass-transfer and coating-zone models chosen in a scenario file.\n\n"
      "Examples:\n"
      "  cosim validate scenarios/settling-sphere\n"
      "  cosim run scenarios/settling-sphere --set coupling.end_time=0.2\n"
      "  cosim run scenarios/plasma-coating-bed --set flow_lpm=50\n"
      "  cosim report runs/plasma-coating-bed\n"
      "  cosim ft4 energy runs/ft4-rheometer\n"};
  app.require_subcommand(1);
  std::vector<std::string> sets, unsets;
  std::string scenario;
  const char* set_help =
      "override a value: key.path=value (e.g. coupling.end_time=0.5); a bare name sets a "
      "scenario parameter (e.g. flow_lpm=50); a YAML map or list replaces the whole node (e.g. "
      "'models.coating_zone={shape: sphere, center: [0, 0, 0.01], radius: 0.005}')";
  const char* unset_help =
      "remove a node (and everything below it) before the --set overrides, e.g. "
      "models.coating_zone";

  auto* run =
      app.add_subcommand("run", "Run a scenario (a scenario.yaml, or a folder holding one)");
  run->add_option("scenario", scenario, "scenario file or folder")->required();
  run->add_option("--set", sets, set_help)->take_all();
  run->add_option("--unset", unsets, unset_help)->take_all();
  RunOptions ropt;
  std::string output;
  run->add_option("-o,--output", output,
                  "run folder; refused if it exists and is not empty (default: the scenario's "
                  "output.folder, or a free name beside it)");
  run->add_flag("--overwrite", ropt.overwrite, "reuse the run folder even if it exists");
  run->add_flag("-q,--quiet", ropt.quiet, "no progress line");

  auto* resume = app.add_subcommand(
      "resume",
      "Continue a run from its newest checkpoint, in the same folder (Ctrl-C, a crash or a "
      "time limit stopped it; or make a finished run longer with --set coupling.end_time=...)");
  std::string resume_folder;
  resume->add_option("run", resume_folder, "run folder")->required();
  resume
      ->add_option("--set", sets,
                   "override a value as for run; only coupling.end_time, output, checkpoint, "
                   "transport, checks and observables may differ from the checkpoint's scene")
      ->take_all();
  resume->add_flag("-q,--quiet", ropt.quiet, "no progress line");
  double resume_from = 0;
  auto* from_opt = resume->add_option(
      "--from", resume_from,
      "continue from the checkpoint at this time [s] instead of the newest (ls RUN/checkpoints); "
      "newer ones are moved to RUN/checkpoints/superseded/");

  auto* pack = app.add_subcommand(
      "pack",
      "Copy a stopped run to DEST so that it continues there (another machine or disk): the "
      "scene, the records and the newest checkpoint; logs, older checkpoints, the fluid's time "
      "folders and the particles' dumps left out. Then: cosim resume DEST");
  std::string pack_run, pack_dest;
  pack->add_option("run", pack_run, "run folder (stopped: Ctrl-C writes a checkpoint)")->required();
  pack->add_option("dest", pack_dest, "new folder for the copy (must not exist)")->required();

  auto* val = app.add_subcommand(
      "validate", "Check a scenario and show what it would start and send, without running");
  val->add_option("scenario", scenario, "scenario file or folder")->required();
  val->add_option("--set", sets, "override a value (as for run)")->take_all();
  val->add_option("--unset", unsets, "remove a node (as for run)")->take_all();

  auto* study = app.add_subcommand(
      "study",
      "Error against run time: run variants of a scenario, compare its observables with their "
      "analytic reference (or the finest variant), time each run, mark the Pareto front");
  StudyOptions sopt;
  std::vector<std::string> vary;
  study->add_option("scenario", sopt.scenario, "scenario file or folder")->required();
  study
      ->add_option("--vary", vary,
                   "key=v1,v2,... (repeat for a grid), e.g. --vary coupling.dem_steps=5,10,20")
      ->required()
      ->take_all();
  study->add_option("--set", sopt.sets, "fixed override for every variant (as for run)")
      ->take_all();
  study->add_option("--unset", sopt.unsets, "node removed in every variant (as for run)")
      ->take_all();
  study->add_option("-o,--output", sopt.output, "study folder (default runs/<name>-study)");
  study->add_option("--finest", sopt.finest,
                    "index (0-based, in --vary order) of the variant taken as reference where no "
                    "analytic one exists (default: the slowest)");
  study->add_flag(
      "--no-plots", [&](std::int64_t) { sopt.plots = false; }, "tables only");
  study->add_flag(
      "--rerun", sopt.rerun,
      "run every variant again (default: a variant whose folder holds a completed run of the same "
      "resolved scene is read back, one stopped before its end resumes from its newest "
      "checkpoint, so an interrupted study continues and --finest can be changed for free)");

  auto* bench = app.add_subcommand(
      "bench",
      "Cost of a coupled step against its solvers alone, on the same scene: coupled (its terms "
      "recorded), the particles alone under the recorded forcing and the fluid alone with the "
      "recorded particle terms, per step with phases; the last line reads "
      "'coupled/max(dem,cfd) = R; serial share = S %'");
  BenchOptions bopt;
  bench->add_option("scenario", bopt.scenario, "scenario file or folder")->required();
  bench->add_option("--steps", bopt.steps, "timed coupling steps per stage (default 50)");
  bench->add_option("--warmup", bopt.warmup, "untimed steps before them (default 5)");
  bench->add_option("--set", bopt.sets, "override a value (as for run)")->take_all();
  bench->add_option("--unset", bopt.unsets, "remove a node (as for run)")->take_all();
  bench->add_option("-o,--output", bopt.output,
                    "folder of the stages' run folders (default runs/<scene>-bench)");

  auto* models = app.add_subcommand("models", "List the coupling models this build knows");

  auto* keys = app.add_subcommand(
      "keys",
      "Create the orchestrator's CurveZMQ key file for tcp:// runs if it does not exist (mode "
      "0600), and show a key file's public keys (never a secret one)");
  std::string key_file;
  keys->add_option("file", key_file,
                   "key file (default: $XDG_CONFIG_HOME/cosim/orchestrator.key, else "
                   "~/.config/cosim/orchestrator.key); a participant's RUN/.cosim-NAME.key is "
                   "shown");

  Ft4Options ft4_opt;
  auto* ft4 = addFt4Command(app, ft4_opt);
  BatchOptions batch_opt;
  auto* batch = addBatchCommand(app, batch_opt);

#ifdef COSIM_HAVE_REPORT
  cosim::analysis::ReportOptions rep_opt;
  auto* rep = app.add_subcommand(
      "report", "Analyse run folders: coating statistics, fits, extrapolation, plots, HTML");
  rep->add_option("runs", rep_opt.runs,
                  "run folders (several: one comparison report, e.g. a flow sweep)")
      ->required();
  rep->add_option("-o,--output", rep_opt.output,
                  "report folder (default: RUN/report for one run, report-comparison beside the "
                  "runs for several)");
  rep->add_option("--fit-start", rep_opt.fit_start,
                  "start of the fit window [s] (default: first snapshot)");
  rep->add_option("--fit-end", rep_opt.fit_end,
                  "end of the fit window [s] (default: last snapshot)");
  rep->add_option("--coating-start", rep_opt.coating_start,
                  "time coating starts [s], origin of mu = a1 t");
  rep->add_option("--histograms", rep_opt.histogram_times, "times of the histograms [s]")
      ->delimiter(',');
  rep->add_option("--predict", rep_opt.predict_times, "times of the extrapolated distributions [s]")
      ->delimiter(',');
  rep->add_option("--predict-until", rep_opt.predict_until,
                  "horizon of the CV prediction [s] (default 3600)");
  rep->add_option("--band", rep_opt.band,
                  "relative band on a2 drawn around the CV prediction (default 0.2)");
  rep->add_option(
      "--bootstrap", rep_opt.bootstrap_resamples,
      "particle-bootstrap resamples for the errors of a1, a2 (default 100; 0 = HC3 errors only)");
  rep->add_option(
      "--uncoated-threshold", rep_opt.uncoated_relative,
      "a particle counts as never coated below this fraction of the mean coating (default 1e-6)");
  rep->add_option("--coating-density", rep_opt.coating_density,
                  "density of the coating layer [kg/m3] for its thickness (default: the scene's "
                  "parameter coating_density, else 1500)");
  rep->add_option("--u-mf", rep_opt.u_mf,
                  "minimum fluidization velocity [m/s] for u/u_mf (default: the scene's parameter "
                  "u_mf, else Wen-Yu for the real grains)");
  rep->add_option("--check-mass-balance", rep_opt.mass_balance_limit_percent,
                  "exit 3 if a run's mass-balance error exceeds this many percent (e.g. 0.01)");
  std::vector<std::string> mixing;
  rep->add_option(
      "--mixing", mixing,
      "override a mixing criterion, NAME=VALUE (names in docs/analysis.md, e.g. "
      "max_uncoated_share=0.3); the report then says it was judged with non-default criteria");
  bool no_plots = false;
  rep->add_flag("--no-plots", no_plots, "numbers and HTML only, no matplotlib");
  rep->add_flag("--no-batch{false}", rep_opt.batch,
                "leave out the whole batch by the long-time model (cosim batch)");

  cosim::analysis::PivCommandOptions piv_opt;
  auto* piv = app.add_subcommand(
      "piv",
      "The particle velocity a PIV camera sees through the front wall: the time-averaged "
      "vertical velocity of the parcels next to it on a grid, and its profiles across the width "
      "(RUN/piv/grid.csv, profiles.csv); docs/calibration-validation.md section 2");
  piv->add_option("run", piv_opt.run, "run folder")->required();
  piv->add_option("--from", piv_opt.from,
                  "snapshots at t >= this count [s] (default: the scene parameter piv_discard, "
                  "else 0)");
  piv->add_option("--to", piv_opt.to, "snapshots at t <= this count [s] (default: the end)");
  piv->add_option("--depth", piv_opt.depth,
                  "a parcel is seen when its centre lies within this distance of the front wall "
                  "[m] (default: within its own diameter)");
  piv->add_option("--cell", piv_opt.cell, "grid cell and profile band [m] (default 0.004)");
  piv->add_option("--blocks", piv_opt.blocks,
                  "blocks of consecutive snapshots for the profiles' standard errors (batch "
                  "means; default 10)")
      ->check(CLI::Range(2, 100000));
  piv->add_option("--heights", piv_opt.heights,
                  "profile heights above the bottom [m] (default 0.13,0.15)")
      ->delimiter(',');
  piv->add_option("--wall-y", piv_opt.wall_y,
                  "the front wall's plane y [m] (default: scene parameter piv_front_wall_y)");
  piv->add_option("--x-min", piv_opt.x_min, "grid's left edge [m] (default: piv_x_min)");
  piv->add_option("--x-max", piv_opt.x_max, "grid's right edge [m] (default: piv_x_max)");
  piv->add_option("--z-min", piv_opt.z_min, "grid's bottom [m] (default 0)");
  piv->add_option("--z-max", piv_opt.z_max, "grid's top [m] (default: piv_z_max)");
  piv->add_option("-o,--output", piv_opt.output,
                  "folder of the CSV files and piv.png (default RUN/piv)");
  piv->add_flag("--no-plots{false}", piv_opt.plots, "the CSV files only, no piv.png");

  cosim::analysis::PivCompareCommandOptions pivc_opt;
  auto* pivc = app.add_subcommand(
      "piv-compare",
      "Mean absolute error of simulated PIV profiles against measured ones, per profile and per "
      "region (upward core, downward sides); the CSV format is in docs/calibration-validation.md");
  pivc->add_option("simulated", pivc_opt.simulated,
                   "run folder (its piv/profiles.csv, from cosim piv) or a profile CSV")
      ->required();
  pivc->add_option("measured", pivc_opt.measured, "measured profiles (CSV: height_m,x_m,vz_m_s)")
      ->required();
  std::vector<double> core_band;
  pivc->add_option("--core", core_band,
                   "x0,x1 [m]: the core is x0 <= x <= x1 (default: where the measured vz > 0)")
      ->delimiter(',')
      ->expected(2);
  pivc->add_option("-o,--output", pivc_opt.output,
                   "comparison CSV (default: comparison.csv beside the simulated profiles); "
                   "its plot has the same name ending .png");
  pivc->add_flag("--no-plots{false}", pivc_opt.plots, "the CSV only, no PNG");
  std::vector<std::string> pivc_labels;
  pivc->add_option("--labels", pivc_labels,
                   "A,B: the two profiles' names in the plot's legend (default "
                   "simulated,measured; e.g. 'cg 5,cg 10' when a run is compared with another)")
      ->delimiter(',')
      ->expected(2);
#endif

  CLI11_PARSE(app, argc, argv);

  try {
    if (*val) return validate(scenario, sets, unsets);
    if (*keys) return keysCommand(key_file, std::cout);
    if (*ft4) return runFt4Command(*ft4, ft4_opt, std::cout, std::cerr);
    if (*batch) return runBatchCommand(batch_opt, std::cout, std::cerr);
    if (*study) {
      for (const auto& v : vary) sopt.vary.push_back(parseVary(v));
      // Ctrl-C or SIGTERM: the running variant checkpoints and stops, and so does the study
      std::signal(SIGINT, onSignal);
      std::signal(SIGTERM, onSignal);
      std::signal(SIGPIPE, SIG_IGN);
      return runStudy(sopt);
    }
    if (*models) {
      auto& r = cosim::models::Registry::instance();
      std::cout << "drag laws: " << join(r.dragNames())
                << "\nundisturbed gas velocity (models.drag.undisturbed_velocity): "
                << join(cosim::models::undisturbedVelocityNames())
                << " (calibrated for the gas solver with models.drag.self_disturbance_gain, "
                   "self_disturbance_offset)"
                << "\nforce models: " << join(r.forceNames())
                << "\nmass transfer laws: " << join(r.massTransferNames())
                << "\ncoating zone shapes: " << join(r.zoneNames()) << "\n";
      return 0;
    }
#ifdef COSIM_HAVE_REPORT
    if (no_plots) rep_opt.plots = false;
    for (const auto& m : mixing) {
      std::string names;
      for (const auto& k : cosim::analysis::kMixingCriteria)
        names += (names.empty() ? "" : ", ") + std::string(k.name);
      const auto eq = m.find('=');
      const cosim::analysis::MixingCriterion* criterion = nullptr;
      for (const auto& k : cosim::analysis::kMixingCriteria) {
        if (eq != std::string::npos && m.compare(0, eq, k.name) == 0 && eq == std::strlen(k.name))
          criterion = &k;
      }
      char* end = nullptr;
      const double value = criterion ? std::strtod(m.c_str() + eq + 1, &end) : 0.0;
      if (!criterion || end == m.c_str() + eq + 1 || *end != '\0' || !(value >= 0)) {
        std::cerr << "cosim report: --mixing " << m
                  << ": expected NAME=VALUE with VALUE >= 0 and NAME one of " << names << "\n";
        return 2;
      }
      rep_opt.criteria.*criterion->value = value;
    }
    if (*rep) return cosim::analysis::runReport(rep_opt);
    if (*piv) return cosim::analysis::runPivCommand(piv_opt, std::cout);
    if (*pivc) {
      if (!core_band.empty()) {
        if (!(core_band[0] < core_band[1])) {
          std::cerr << "cosim piv-compare: --core " << core_band[0] << "," << core_band[1]
                    << ": expected x0,x1 with x0 < x1 [m]\n";
          return 2;
        }
        pivc_opt.core_band = std::make_pair(core_band[0], core_band[1]);
      }
      if (!pivc_labels.empty()) {
        pivc_opt.simulated_label = pivc_labels[0];
        pivc_opt.measured_label = pivc_labels[1];
      }
      return cosim::analysis::runPivCompareCommand(pivc_opt, std::cout);
    }
#endif
    if (*pack) {
      PackResult p;
      try {
        p = packRun(pack_run, pack_dest, loadRunScene(pack_run));
      } catch (const std::exception& e) {
        std::cerr << "cosim pack: " << e.what() << "\n";
        return 1;
      }
      std::cout << "cosim: packed " << pack_run << " into " << pack_dest << ": "
                << byteText(p.copied_bytes) << " in " << p.copied_files
                << " files, continuing from the checkpoint at t = "
                << p.checkpoint.filename().string() << " s\n";
      for (const auto& [kind, bytes] : p.left_out)
        std::cout << "  left out " << kind << ": " << byteText(bytes) << "\n";
      std::cout << "  continue it with: cosim resume " << pack_dest
                << " (the same cosim and solvers; add --set coupling.end_time=T to go further)\n";
      return 0;
    }
    if (*resume) {
      Scenario sc = loadRunScene(resume_folder, sets);
      std::signal(SIGINT, onSignal);
      std::signal(SIGTERM, onSignal);
      ropt.resume = std::filesystem::absolute(resume_folder);
      if (from_opt->count() > 0) ropt.resume_from = resume_from;
      Coupler c(std::move(sc), ropt);
      RunResult r = c.run();
      if (r.exit_code != 0) std::cerr << "\ncosim: run stopped\n" << r.message << "\n";
      return r.exit_code;
    }
    if (*bench) {
      std::signal(SIGINT, onSignal);
      std::signal(SIGTERM, onSignal);
      std::signal(SIGPIPE, SIG_IGN);
      if (bopt.steps == 0) {
        std::cerr << "cosim bench: --steps must be >= 1\n";
        return 2;
      }
      return runBench(bopt, std::cout);
    }
    if (*run) {
      Scenario sc = loadScenario(scenario, sets, unsets);
      if (!output.empty()) ropt.output = output;
      std::signal(SIGINT, onSignal);
      std::signal(SIGTERM, onSignal);
      std::signal(SIGPIPE, SIG_IGN);
      Coupler c(std::move(sc), ropt);
      RunResult r = c.run();
      if (r.exit_code != 0) {
        std::cerr << "\ncosim: run stopped\n" << r.message << "\n";
        return r.exit_code;
      }
      for (const auto& o : r.observables) {
        if (!o.undefined.empty()) {
          std::cout << "cosim: " << o.name << ": no value (" << o.undefined << ")\n";
          continue;
        }
        std::cout << "cosim: " << o.name << " = " << o.value;
        if (o.reference)
          std::cout << " (reference " << *o.reference << ", relative error " << *o.relative_error
                    << ")";
        std::cout << "\n";
      }
      std::cout << "cosim: results in " << r.folder.string() << "\n";
      return 0;
    }
  } catch (const ScenarioError& e) {
    std::cerr << "cosim: invalid scenario\n  " << cosim::util::cutLongQuotes(e.what()) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "cosim: " << cosim::util::cutLongQuotes(e.what()) << "\n";
    return 1;
  }
  return 0;
}
