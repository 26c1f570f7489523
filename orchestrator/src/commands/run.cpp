// cosim run SCENARIO [--set K=V] [--unset K] [-o FOLDER] [--overwrite] [-q]
#include <iostream>
#include <memory>

#include "commands.h"
#include "coupler.h"
#include "scenario.h"
#include "step_retreat.h"

namespace cosim::orchestrator {

void addRunCommand(CLI::App& app, Commands& commands) {
  struct Options {
    std::string scenario, output;
    std::vector<std::string> sets, unsets;
    RunOptions run;
  };
  auto o = std::make_shared<Options>();
  auto* run =
      app.add_subcommand("run", "Run a scenario (a scenario.yaml, or a folder holding one)");
  run->add_option("scenario", o->scenario, "scenario file or folder")->required();
  run->add_option("--set", o->sets, kSetHelp)->take_all();
  run->add_option("--unset", o->unsets, kUnsetHelp)->take_all();
  run->add_option("-o,--output", o->output,
                  "run folder; refused if it exists and is not empty (default: the scenario's "
                  "output.folder, or a free name beside it)");
  run->add_flag("--overwrite", o->run.overwrite, "reuse the run folder even if it exists");
  run->add_flag("-q,--quiet", o->run.quiet, "no progress line");
  commands.push_back({run, [o] {
                        Scenario sc = loadScenario(o->scenario, o->sets, o->unsets);
                        if (!o->output.empty()) o->run.output = o->output;
                        catchStopSignals();
                        o->run.stop = &processStop();
                        return reportRunEnd(runThroughStiffStretches(std::move(sc), o->run));
                      }});
}

}  // namespace cosim::orchestrator
