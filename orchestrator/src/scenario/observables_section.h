// observables: named results a run measures at the end, each a quantity (observables.h gives
// the grammar) with an optional analytic reference.
#pragma once

#include <string>
#include <vector>

#include "observables.h"
#include "scenario/context.h"

namespace cosim::orchestrator {

using ObservablesSection = std::vector<ObservableSpec>;

const std::vector<KeySpec>& observableKeys();

ObservablesSection parseObservables(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator
