// Runs a verification scene in-process through the orchestrator (the participants are the
// real cosimFoam and cosim-liggghts processes).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "coupler.h"
#include "scenario.h"

namespace cosim::verification {

inline orchestrator::RunResult runScene(const std::string& scene,
                                        const std::vector<std::string>& sets,
                                        const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path out =
      fs::temp_directory_path() / ("cosim-verify-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(out);
  orchestrator::Scenario sc =
      orchestrator::loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios" / scene, sets);
  orchestrator::RunOptions o;
  o.quiet = true;
  o.output = out;
  orchestrator::Coupler c(std::move(sc), o);
  return c.run();
}

}  // namespace cosim::verification
