// Options of the particles participant when its adapter is `liggghts` (the participant's
// `options:` node of the scenario, received as Welcome.config_yaml), declared with their
// defaults and meaning in AdapterOptions::specs() (docs/liggghts.md shows that table).
#pragma once

#include <string>
#include <vector>

#include "cosim/util/adapter_options.h"

namespace cosim::liggghts {

enum class DtCheckPolicy { refuse, warn, off };

struct AdapterOptions {
  std::string script;
  double impact_speed = 2.0;
  DtCheckPolicy dt_check = DtCheckPolicy::refuse;

  // Throws cosim::InputError naming the key, what was expected and what to do.
  static AdapterOptions parse(const std::string& yaml_text);
  static const std::vector<util::OptionSpec>& specs();
};

}  // namespace cosim::liggghts
