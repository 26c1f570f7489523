// cosim models: the coupling models this build knows
#include <iostream>

#include "commands.h"
#include "cosim/models/drag/undisturbed_velocity.h"
#include "cosim/models/registry.h"

namespace cosim::orchestrator {

namespace {
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none)" : s;
}
}  // namespace

void addModelsCommand(CLI::App& app, Commands& commands) {
  auto* models = app.add_subcommand("models", "List the coupling models this build knows");
  commands.push_back({models, [] {
                        auto& r = cosim::models::Registry::instance();
                        std::cout << "drag laws: " << join(r.dragNames())
                                  << "\nundisturbed gas velocity "
                                     "(models.drag.undisturbed_velocity): "
                                  << join(cosim::models::undisturbedVelocityNames())
                                  << " (calibrated for the gas solver with "
                                     "models.drag.self_disturbance_gain, "
                                     "self_disturbance_offset)"
                                  << "\nforce models: " << join(r.forceNames())
                                  << "\nmass transfer laws: " << join(r.massTransferNames())
                                  << "\ncoating zone shapes: " << join(r.zoneNames()) << "\n";
                        return 0;
                      }});
}

}  // namespace cosim::orchestrator
