// output: where a run writes (its run folder) and how often it writes particle snapshots. A
// scenario never names a place outside the folder cosim runs in: names and folders use a safe
// set of characters and no '..' (a folder elsewhere is the user's choice: `cosim run -o`).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct OutputSection {
  std::filesystem::path folder;  // run folder (absolute)
  double interval = 0.0;         // particle snapshots [s]; 0 = every step

  static const std::vector<KeySpec>& keys();
};

// `name`: the scene's name, which gives the default folder runs/NAME.
OutputSection parseOutput(const YAML::Node& node, const Context& ctx, const std::string& name);

// Empty if `name` is a safe file name (letters, digits, '.', '_', '-', '+'; not starting with '.'
// or '-'; at most limits::kMaxNameLength characters), else what is wrong with it.
std::string unsafeNameReason(const std::string& name);

}  // namespace cosim::orchestrator
