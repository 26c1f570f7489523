// Options of the particles participant when its adapter is `liggghts` (the participant's
// `options:` node of the scenario, received as Welcome.config_yaml):
//   script: in.liggghts      LIGGGHTS input script, relative to the participant's folder (required)
//   impact_speed: 2.0        [m/s] largest expected impact speed, for the Hertz contact time
//   dt_check: refuse         refuse | warn | off: what to do with an unstable DEM time step
#pragma once

#include <string>

namespace cosim::liggghts {

enum class DtCheckPolicy { refuse, warn, off };

struct AdapterOptions {
  std::string script;
  double impact_speed = 2.0;
  DtCheckPolicy dt_check = DtCheckPolicy::refuse;

  // Throws std::runtime_error naming the key, what was expected and what to do.
  static AdapterOptions parse(const std::string& yaml_text);
};

}  // namespace cosim::liggghts
