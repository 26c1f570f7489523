// cosim resume RUN [--set K=V] [--from T] [-q]
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "coupler.h"
#include "scenario.h"
#include "step_retreat.h"

namespace cosim::orchestrator {

void addResumeCommand(CLI::App& app, Commands& commands) {
  struct Options {
    std::string folder;
    std::vector<std::string> sets;
    double from = 0;
    RunOptions run;
  };
  auto o = std::make_shared<Options>();
  auto* resume = app.add_subcommand(
      "resume",
      "Continue a run from its newest checkpoint, in the same folder (Ctrl-C, a crash or a "
      "time limit stopped it; or make a finished run longer with --set coupling.end_time=...)");
  resume->add_option("run", o->folder, "run folder")->required();
  resume
      ->add_option("--set", o->sets,
                   "override a value as for run; only coupling.end_time, coupling.dt with "
                   "coupling.dem_steps (the DEM step kept), output, checkpoint, transport, checks "
                   "and observables may differ from the checkpoint's scene")
      ->take_all();
  resume->add_flag("-q,--quiet", o->run.quiet, "no progress line");
  auto* from = resume->add_option(
      "--from", o->from,
      "continue from the checkpoint at this time [s] instead of the newest (ls RUN/checkpoints); "
      "newer ones are moved to RUN/checkpoints/superseded/");
  commands.push_back({resume, [o, from] {
                        Scenario sc = loadRunScene(o->folder, o->sets);
                        catchStopSignals(false);
                        o->run.stop = &processStop();
                        o->run.resume = std::filesystem::absolute(o->folder);
                        if (from->count() > 0) o->run.resume_from = o->from;
                        return reportRunEnd(runThroughStiffStretches(std::move(sc), o->run));
                      }});
}

}  // namespace cosim::orchestrator
