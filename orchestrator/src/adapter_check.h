// `cosim validate` asks each adapter whether it accepts the scene, without starting a run: the
// case files are templated into a temporary folder as the run would, the Welcome the run would
// send is written next to them, and the adapter's executable runs with --check-options on it
// (its options, the files they name, the script's time step, the mesh's patches, the MPI ranks;
// docs/scenario.md). Nothing is started, nothing is written outside the temporary folder, which
// is removed afterwards.
#pragma once

#include <string>
#include <vector>

#include "plan.h"
#include "scenario.h"

namespace cosim::orchestrator {

// Seconds an adapter may take to answer --check-options.
inline constexpr double kAdapterCheckSeconds = 60.0;

// Throws ScenarioError naming the scenario file, the participant and the adapter's reason when
// an adapter refuses. Returns one line per participant: what was checked, or why it was not
// (a custom adapter, which need not know --check-options).
std::vector<std::string> checkAdapters(const Scenario& sc, const Plan& plan,
                                       double timeout_s = kAdapterCheckSeconds);

}  // namespace cosim::orchestrator
