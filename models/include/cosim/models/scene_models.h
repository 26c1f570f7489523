// The coupling laws of one scene, chosen by name and built together: what step 3 of the coupling
// step evaluates over the parcels (coupling_terms.h). Whoever runs the models builds them from
// the same choices: the orchestrator from the scenario's `models:` section on the central data
// path, a participant from the choices the orchestrator sends it (cosim/link/models_wire.h).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/models/drag/wake_buildup.h"
#include "cosim/models/model.h"
#include "cosim/models/parameters.h"

namespace cosim::models {

// One law: its registered name and its parameters as the scene gives them.
struct ModelChoice {
  std::string law;
  Parameters params;
};

// Every law of a scene, and the plugins that register laws beyond the built-in ones.
struct SceneModelChoices {
  std::optional<ModelChoice> drag;
  std::vector<ModelChoice> forces;
  std::optional<ModelChoice> mass_transfer;
  std::optional<ModelChoice> coating_zone;
  std::vector<std::string> plugins;  // shared libraries that register laws (Registry::loadPlugin)
};

// The instantiated laws of a scene.
struct SceneModels {
  std::unique_ptr<DragLaw> drag;
  std::vector<std::unique_ptr<ForceModel>> forces;
  std::unique_ptr<MassTransferLaw> mass_transfer;
  std::unique_ptr<CoatingZone> zone;
  // With undisturbed_velocity 'self_disturbance_transient': every parcel's force history, kept
  // between steps (and in checkpoints) by whoever evaluates the terms; null otherwise.
  std::unique_ptr<WakeBuildup> wake;
  // The parcels may be split into parts evaluated at once (evaluateTerms' threads): no law
  // carries work across parcels, and no law comes from a plugin (whose methods are not known to
  // run safely at once).
  bool splittable = false;
};

// Builds every law, the plugins' included once loaded (Registry::loadPlugin: the orchestrator
// loads them when it reads the scene); ModelError names the law and the parameter.
SceneModels makeSceneModels(const SceneModelChoices& choices);

}  // namespace cosim::models
