// checkpoint: how often the whole coupled state is saved under RUN/checkpoints/<time>/ and how
// many are kept (docs/restarts.md). `cosim resume RUN` continues from the newest.
#pragma once

#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct CheckpointSection {
  double interval = 0.0;  // simulated seconds; 0 = none (Ctrl-C still writes one)
  int keep = 3;           // the newest ones kept

  static const std::vector<KeySpec>& keys();
};

CheckpointSection parseCheckpoint(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator
