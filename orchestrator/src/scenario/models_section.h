// models: the coupling laws of a scene (drag, other fluid forces, mass transfer, coating zone),
// each a registered name with its parameters, and the plugins that register more.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cosim/models/scene_models.h"
#include "scenario/context.h"

namespace cosim::orchestrator {

// A law as the scene names it (its registered name and parameters), and the line it is on.
struct ModelSpec : models::ModelChoice {
  int line = 0;
};

struct ModelsSection {
  std::optional<ModelSpec> drag;
  std::vector<ModelSpec> forces;
  std::optional<ModelSpec> mass_transfer;
  std::optional<ModelSpec> coating_zone;
  std::vector<std::filesystem::path> plugins;

  // The scene needs fluid fields (drag, forces or mass transfer).
  bool needsFluid() const { return drag || !forces.empty() || mass_transfer; }
  // The laws and plugins as every runner of the models takes them (cosim/models/scene_models.h).
  models::SceneModelChoices choices() const;

  static const std::vector<KeySpec>& keys();
  // The keys every drag law takes beside its own parameters (read by the registry's drag
  // wrapper, models/src/registry.cpp, for built-in laws and plugins alike).
  static const std::vector<KeySpec>& dragKeys();
};

// Every law is built once here, so that unknown names and parameters are errors of the file.
// `dir`: the scenario's folder (plugins: is relative to it).
ModelsSection parseModels(const YAML::Node& node, const Context& ctx,
                          const std::filesystem::path& dir);

}  // namespace cosim::orchestrator
