// cosim models: the coupling models this build knows
#include <iostream>

#include "commands.h"
#include "cosim/models/drag/undisturbed_velocity.h"
#include "cosim/models/registry.h"

namespace cosim::orchestrator {

namespace {}  // namespace

void addModelsCommand(CLI::App& app, Commands& commands) {
  auto* models = app.add_subcommand("models", "List the coupling models this build knows");
  commands.push_back({models, [] {
                        auto& r = cosim::models::Registry::instance();
                        std::cout << "drag laws: " << joinNames(r.dragNames())
                                  << "\nundisturbed gas velocity "
                                     "(models.drag.undisturbed_velocity): "
                                  << joinNames(cosim::models::undisturbedVelocityNames())
                                  << " (calibrated for the gas solver with "
                                     "models.drag.self_disturbance_gain, "
                                     "self_disturbance_offset)"
                                  << "\nforce models: " << joinNames(r.forceNames())
                                  << "\nmass transfer laws: " << joinNames(r.massTransferNames())
                                  << "\ncoating zone shapes: " << joinNames(r.zoneNames()) << "\n";
                        return 0;
                      }});
}

}  // namespace cosim::orchestrator
