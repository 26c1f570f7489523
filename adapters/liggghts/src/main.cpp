// cosim-liggghts: the LIGGGHTS particles participant.
//   [mpirun -np N] cosim-liggghts --endpoint <addr> --name <participant> --run-id <id>
// Rank 0 talks to the orchestrator; the other ranks execute what rank 0 broadcasts.
#include <mpi.h>

#include <cstdio>
#include <exception>
#include <vector>

#include "cosim/liggghts/adapter_options.h"
#include "cosim/liggghts/liggghts_solver.h"
#include "cosim/liggghts/scene_check.h"
#include "cosim/link/peer_terms.h"
#include "cosim/link/session.h"
#include "cosim/util/errors.h"

int main(int argc, char** argv) {
  if (cosim::link::checkOptionsRequested(argc, argv)) {
    // `cosim validate` (or the option table): no MPI, no LIGGGHTS; only what the files tell
    try {
      const auto options = cosim::link::ParticipantOptions::parse(
          argc, argv, "cosim-liggghts --check-options FILE: check a scene, start nothing");
      if (!options) return 0;
      if (options->options_reference) {
        std::fputs(cosim::util::optionsTable(cosim::liggghts::AdapterOptions::specs()).c_str(),
                   stdout);
        return 0;
      }
      return cosim::link::checkSceneOptions(
          *options, [](const cosim::wire::Welcome& w, int) { cosim::liggghts::checkScene(w); });
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cosim-liggghts: %s\n", e.what());
      return cosim::exit_code::input;
    }
  }
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  cosim::liggghts::LiggghtsSolver solver(MPI_COMM_WORLD);
  int rc = 0;
  if (rank == 0) {
    try {
      std::vector<std::string> rest;
      const auto options = cosim::link::ParticipantOptions::parse(
          argc, argv,
          "cosim-liggghts: the LIGGGHTS particle participant; runs the scene's LIGGGHTS script "
          "(options: in the scenario, docs/liggghts.md). Normally started by `cosim run`, under "
          "mpirun for several ranks.",
          &rest);
      if (options && !rest.empty())
        throw cosim::InputError("unknown argument '" + rest.front() +
                                "'; usage: cosim-liggghts --endpoint <addr> --name <participant> "
                                "--run-id <id> (--help for all options)");
      cosim::link::ScenePeerTerms laws;  // coupling.data_path: peer
      if (options) rc = cosim::link::runParticipant(solver, *options, &laws);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cosim-liggghts: %s\n", e.what());
      rc = 2;
    }
    if (solver.mustAbort()) MPI_Abort(MPI_COMM_WORLD, rc == 0 ? 1 : rc);
    solver.releaseOtherRanks();
  } else {
    rc = solver.serve();
    if (solver.mustAbort()) MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return rc;
}
