// cosim: the orchestrator's command line. Each subcommand is a file of commands/.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands/commands.h"
#include "cosim/util/errors.h"
#include "cosim/util/long_quotes.h"
#include "scenario.h"

using namespace cosim::orchestrator;

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
      "  cosim batch runs/plasma-coating-bed --until 3600\n"
      "  cosim ft4 energy runs/ft4-rheometer\n"};
  app.require_subcommand(1);
  Commands commands;
  for (auto add :
       {addRunCommand, addResumeCommand, addPackCommand, addValidateCommand, addStudyCommand,
        addBenchCommand, addModelsCommand, addReferenceCommand, addKeysCommand, addFt4Commands,
        addBatchCommandLine, addReportCommand, addPivCommand, addPivCompareCommand})
    add(app, commands);

  CLI11_PARSE(app, argc, argv);
  stopAtOnceOnSignals();  // run, resume, study and bench catch them to stop with a checkpoint
  try {
    for (const auto& c : commands)
      if (*c.app) return c.run();
  } catch (const ScenarioError& e) {
    std::cerr << "cosim: invalid scenario\n  " << cosim::util::cutLongQuotes(e.what()) << "\n";
    return cosim::exit_code::input;
  } catch (const std::exception& e) {
    // The exit code of each kind of error (cosim/util/errors.h); what a command was given is
    // wrong unless the error says otherwise.
    std::cerr << "cosim: " << cosim::util::cutLongQuotes(e.what()) << "\n";
    return cosim::exitCodeOf(cosim::kindOf(e, cosim::ErrorKind::input));
  }
  return cosim::exit_code::ok;
}
