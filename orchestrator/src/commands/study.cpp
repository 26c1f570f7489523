// cosim study SCENARIO --vary K=v1,v2 [--vary ...] [--set K=V] [-o FOLDER] [--finest N]
#include "study.h"

#include <memory>

#include "commands.h"

namespace cosim::orchestrator {

void addStudyCommand(CLI::App& app, Commands& commands) {
  struct Options {
    StudyOptions study;
    std::vector<std::string> vary;
  };
  auto o = std::make_shared<Options>();
  auto& s = o->study;
  auto* study = app.add_subcommand(
      "study",
      "Error against run time: run variants of a scenario, compare its observables with their "
      "analytic reference (or the finest variant), time each run, mark the Pareto front");
  study->add_option("scenario", s.scenario, "scenario file or folder")->required();
  study
      ->add_option("--vary", o->vary,
                   "key=v1,v2,... (repeat for a grid), e.g. --vary coupling.dem_steps=5,10,20")
      ->required()
      ->take_all();
  study->add_option("--set", s.sets, "fixed override for every variant (as for run)")->take_all();
  study->add_option("--unset", s.unsets, "node removed in every variant (as for run)")->take_all();
  study->add_option("-o,--output", s.output, "study folder (default runs/<name>-study)");
  study->add_option("--finest", s.finest,
                    "index (0-based, in --vary order) of the variant taken as reference where no "
                    "analytic one exists (default: the slowest)");
  study->add_flag("--no-plots{false}", s.plots, "tables only");
  study->add_flag(
      "--rerun", s.rerun,
      "run every variant again (default: a variant whose folder holds a completed run of the same "
      "resolved scene is read back, one stopped before its end resumes from its newest "
      "checkpoint, so an interrupted study continues and --finest can be changed for free)");
  commands.push_back({study, [o] {
                        for (const auto& v : o->vary) o->study.vary.push_back(parseVary(v));
                        // Ctrl-C or SIGTERM: the running variant checkpoints and stops, and so
                        // does the study
                        catchStopSignals();
                        o->study.stop = &processStop();
                        return runStudy(o->study);
                      }});
}

}  // namespace cosim::orchestrator
