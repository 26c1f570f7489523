// cosim bench SCENARIO|--from RUN [--steps N] [--warmup N] [--peer] [--set K=V] [-o FOLDER]
#include "../bench.h"

#include <iostream>
#include <memory>

#include "../cli_checks.h"
#include "commands.h"

namespace cosim::orchestrator {

void addBenchCommand(CLI::App& app, Commands& commands) {
  auto o = std::make_shared<BenchOptions>();
  auto* bench = app.add_subcommand(
      "bench",
      "Cost of a coupled step against its solvers alone, on the same scene: coupled (its terms "
      "recorded), the particles alone under the recorded forcing and the fluid alone with the "
      "recorded particle terms, per step with phases (and with --peer the coupled step on the "
      "rank-to-rank data path); the last line reads "
      "'coupled/max(dem,cfd) = R; serial share = S %'");
  auto* scene = bench->add_option("scenario", o->scenario, "scenario file or folder");
  auto* from = bench->add_option(
      "--from", o->from,
      "instead of a scenario: a stopped run (its newest checkpoint), to time the steps of a bed "
      "already fluidized; each stage continues a copy of it, the run is not written");
  scene->excludes(from);
  from->excludes(scene);
  bench->add_option("--steps", o->steps, "timed coupling steps per stage (default 50)")
      ->check(cli::wholeNumber(1, 1000000000));
  bench->add_option("--warmup", o->warmup, "untimed steps before them (default 5)")
      ->check(cli::wholeNumber(0, 1000000000));
  bench->add_flag("--peer", o->peer,
                  "also time the coupled step on the rank-to-rank data path "
                  "(coupling.data_path: peer; its own line before the last); taken when the "
                  "scene sets that path; not with --from");
  bench->add_option("--set", o->sets, "override a value (as for run)")->take_all();
  bench->add_option("--unset", o->unsets, "remove a node (as for run)")->take_all();
  bench->add_option("-o,--output", o->output,
                    "folder of the stages' run folders (default runs/<scene>-bench)");
  commands.push_back({bench, [o] {
                        catchStopSignals();
                        o->stop = &processStop();
                        return runBench(*o, std::cout);
                      }});
}

}  // namespace cosim::orchestrator
