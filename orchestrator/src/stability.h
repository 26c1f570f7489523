// Stability checks before and at the start of a run: each prints its ratio; an unstable setting
// is refused with the value that would work, a doubtful one is a warning.
#pragma once

#include <string>
#include <vector>

#include "cosim/link/particle_data.h"
#include "plan.h"
#include "scenario.h"

namespace cosim::orchestrator {

struct StabilityReport {
  std::vector<std::string> lines;     // every check with its ratio
  std::vector<std::string> refusals;  // unstable: what is wrong and what would work
};

StabilityReport checkBeforeRun(const Scenario& sc, const SceneModels& models, const Plan& plan,
                               const link::ParticleData& initial_state);

}  // namespace cosim::orchestrator
