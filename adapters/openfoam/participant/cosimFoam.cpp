// cosimFoam: the OpenFOAM participant of a cosim scene.
//   [mpirun -np N] cosimFoam --endpoint ENDPOINT --name NAME [--run-id ID] [-parallel]
// Run in the case folder (the orchestrator makes it the working directory). OpenFOAM's own
// options (-parallel, -case DIR, ...) pass through to Foam::argList.
#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "AdapterSettings.h"
#include "FoamParticipant.h"
#include "RankBridge.h"
#include "SceneCheck.h"
#include "cosim/link/session.h"
#include "cosim/util/errors.h"

namespace {

// Debian's openfoam package keeps its runtime data here; users and tests need to set nothing.
void setFoamEnvironment() {
  setenv("WM_PROJECT_DIR", "/usr/share/openfoam", 0);
  const std::string etc = std::string(std::getenv("WM_PROJECT_DIR")) + "/etc";
  setenv("FOAM_ETC", etc.c_str(), 0);
  setenv("WM_PROJECT", "OpenFOAM", 0);
  setenv("WM_PROJECT_VERSION", "v1912", 0);
  // No signal-handler magic that would hide the session's own error reporting
  setenv("FOAM_SIGFPE", "false", 0);
}

}  // namespace

int main(int argc, char** argv) {
  setFoamEnvironment();

  std::vector<std::string> rest;
  cosim::link::ParticipantOptions options;
  try {
    const auto parsed = cosim::link::ParticipantOptions::parse(
        argc, argv,
        "cosimFoam: the OpenFOAM v1912 fluid participant; solves the gas and the precursor in the "
        "case of the current folder (docs/openfoam.md). Normally started by `cosim run`. "
        "OpenFOAM options (-parallel, -case DIR) may follow.",
        &rest);
    if (!parsed) return 0;  // --help
    options = *parsed;
    if (options.options_reference) {
      std::cout << cosim::util::optionsTable(cosim::foam::adapterSettingSpecs());
      return 0;
    }
    if (!options.check_options.empty()) {
      // `cosim validate`: no MPI, no OpenFOAM; only what the files tell
      return cosim::link::checkSceneOptions(options, [](const cosim::wire::Welcome& w, int ranks) {
        cosim::foam::checkScene(w, ranks);
      });
    }
  } catch (const std::exception& e) {
    std::cerr << "cosimFoam: " << e.what() << "\n"
              << "  OpenFOAM options (-parallel, -case DIR) may follow.\n";
    return cosim::exit_code::input;
  }

  bool parallel = false;
  for (const auto& a : rest) parallel = parallel || a == "-parallel";
  // Started by mpirun or srun on several ranks without -parallel: a decomposed run is meant
  // (otherwise every rank would be a separate serial participant of the same name). srun with
  // PMIx sets no size of its own: the step's task count is Slurm's.
  for (const char* var :
       {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "SLURM_STEP_NUM_TASKS"}) {
    const char* v = std::getenv(var);
    if (!parallel && v != nullptr && std::atoi(v) > 1) {
      parallel = true;
      rest.push_back("-parallel");
    }
  }
  if (parallel) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  }

  std::vector<std::string> foamArgs{argv[0]};
  foamArgs.insert(foamArgs.end(), rest.begin(), rest.end());

  int rc = 0;
  {
    cosim::foam::RankBridge bridge(parallel);
    if (parallel && bridge.size() < 2) {
      std::cerr << "cosimFoam: -parallel needs mpirun -np 2 or more\n";
      MPI_Finalize();
      return cosim::exit_code::input;
    }
    if (bridge.root()) {
      cosim::foam::FoamParticipant solver(bridge, foamArgs);
      rc = cosim::link::runParticipant(solver, options);
      if (parallel) {
        if (rc != 0) bridge.abortAll(rc);  // the other ranks may be waiting mid-step
        bridge.command(cosim::foam::RankCommand::quit);
      }
    } else {
      try {
        rc = cosim::foam::serveRanks(bridge, foamArgs);
      } catch (const std::exception& e) {
        std::cerr << "cosimFoam rank " << bridge.rank() << ": " << e.what() << std::endl;
        bridge.abortAll(1);
      }
    }
  }
  if (parallel) MPI_Finalize();
  return rc;
}
