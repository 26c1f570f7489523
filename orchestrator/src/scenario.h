// The scenario file: what a user writes to describe a scene. Loaded, templated (${expr} with the
// scenario's parameters), overridden (--set key=value) and validated before anything starts.
// Every error names the file, the line, the key, what was expected and what to do.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

#include "expression.h"
#include "scenario/checkpoint_section.h"
#include "scenario/checks_section.h"
#include "scenario/constants_section.h"
#include "scenario/context.h"
#include "scenario/coupling_section.h"
#include "scenario/models_section.h"
#include "scenario/observables_section.h"
#include "scenario/output_section.h"
#include "scenario/participants_section.h"
#include "scenario/transport_section.h"

namespace cosim::orchestrator {

// One struct per section, each parsed next to its concept by its own function
// (scenario/*_section.{h,cpp}), which declares the section's keys with their defaults and
// meaning (docs/scenario.md lists them).
// A parameter the scene marks `show: true`: a derived number a user should see before running
// (a bed's depth, u / u_mf, the estimated cost), printed by `cosim validate` with its doc.
struct ShownParameter {
  std::string name;
  double value;
  std::string doc;
};

struct Scenario {
  std::filesystem::path file;  // absolute path of the scenario file
  std::filesystem::path dir;   // its folder (relative paths are relative to it)
  std::string name;            // a safe file name (it names the run folder)
  std::string description;
  Variables parameters;
  std::vector<ShownParameter> shown;  // parameters marked show: true, in the file's order

  ParticipantsSection participants;  // as written (may include unused ones)
  CouplingSection coupling;
  ConstantsSection constants;  // scene constants (is-a models::SceneConstants) + material
  ModelsSection models;
  OutputSection output;
  CheckpointSection checkpoint;
  TransportSection transport;
  ChecksSection checks;
  ObservablesSection observables;  // measured at the end, with analytic references

  YAML::Node resolved;  // the scenario after templating and --set, as run
  // The command line's --set overrides it was loaded with ("key.path=value"), so that a check
  // made later (the adapters' own) can say which of them touched what it refuses
  std::vector<std::string> overrides;
};

// The keys of the file's top level, and of a parameter written as a map, declared as each
// section declares its own (the reference, docs/scenario-reference.md, is made from them).
const std::vector<KeySpec>& topLevelKeys();
const std::vector<KeySpec>& parameterKeys();

// Loads and validates. `sets` are "key.path=value" overrides (a bare name sets a parameter; a
// YAML list or map as value replaces the whole node); `unsets` are "key.path" names of nodes to
// remove, applied before the sets. Errors in overridden values name the override.
Scenario loadScenario(const std::filesystem::path& file, const std::vector<std::string>& sets = {},
                      const std::vector<std::string>& unsets = {});

// Same from text (for tests); `origin` is the name used in messages.
Scenario parseScenario(const std::string& text, const std::filesystem::path& origin,
                       const std::vector<std::string>& sets = {},
                       const std::vector<std::string>& unsets = {});

// The scene a run folder was run with: RUN/scenario.resolved.yaml, read with the original
// scenario file as origin (relative paths in it are relative to that file's folder), `sets` on
// top (cosim resume, cosim pack).
Scenario loadRunScene(const std::filesystem::path& run, const std::vector<std::string>& sets = {});

}  // namespace cosim::orchestrator
