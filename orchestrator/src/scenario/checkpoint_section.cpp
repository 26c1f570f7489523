#include "scenario/checkpoint_section.h"

#include <cmath>

namespace cosim::orchestrator {

const std::vector<KeySpec>& CheckpointSection::keys() {
  static const std::vector<KeySpec> k = {
      {"interval", "0",
       "simulated seconds between checkpoints of the whole coupled state, plus one at the end; "
       "0 = none (Ctrl-C still writes one)"},
      {"keep", "3", "how many of the newest checkpoints are kept, 1 to 1000"},
  };
  return k;
}

CheckpointSection parseCheckpoint(const YAML::Node& c, const Context& ctx) {
  CheckpointSection out;
  if (!ctx.section(c, "checkpoint", "{ interval: SECONDS, keep: N }")) return out;
  ctx.allowOnly(c, "checkpoint", CheckpointSection::keys());
  if (c["interval"]) {
    out.interval = ctx.number(c["interval"], "checkpoint.interval");
    if (!(out.interval >= 0) || !std::isfinite(out.interval))
      ctx.fail(c["interval"], "checkpoint.interval",
               "must be >= 0 simulated seconds (0 = no periodic checkpoints)");
  }
  if (c["keep"]) {
    const double k = ctx.number(c["keep"], "checkpoint.keep");
    if (!(k >= 1) || k != std::floor(k) || k > 1000)
      ctx.fail(c["keep"], "checkpoint.keep", "must be a whole number of checkpoints, 1 to 1000");
    out.keep = static_cast<int>(k);
  }
  return out;
}

}  // namespace cosim::orchestrator
