// The one `main` of the analytic adapters: options, `--check-options` (configuring is the whole
// check: their options are all they read), the participant loop, and the exit code of any error
// (cosim/util/errors.h). `Solver` is default-constructible and has configure(Welcome).
// `peer_terms`: a particle adapter's coupling laws for coupling.data_path: peer (none for a fluid).
#pragma once

#include <iostream>
#include <string>

#include "cosim/link/session.h"
#include "cosim/util/adapter_options.h"
#include "cosim/util/errors.h"

namespace cosim::analytic {

template <class Solver>
int analyticMain(int argc, char** argv, const std::string& program, const std::string& what,
                 link::PeerTerms* peer_terms = nullptr) {
  try {
    const auto opts = link::ParticipantOptions::parse(argc, argv, program + ": " + what);
    if (!opts) return exit_code::ok;  // --help
    if (opts->options_reference) {
      std::cout << util::optionsTable(Solver::optionSpecs());
      return exit_code::ok;
    }
    if (!opts->check_options.empty()) {
      return link::checkSceneOptions(*opts, [](const wire::Welcome& w, int) {
        Solver solver;
        solver.configure(w);
      });
    }
    Solver solver;
    return link::runParticipant(solver, *opts, peer_terms);
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return exitCodeOf(kindOf(e, ErrorKind::input));
  }
}

}  // namespace cosim::analytic
