// The scenario key reference: every key a scenario.yaml may hold, with its default and meaning,
// made from the declarations next to the code that reads each key (KeySpec), so that the page a
// user reads (docs/scenario-reference.md, `cosim reference`) cannot drift from the parser.
#pragma once

#include <string>

namespace cosim::orchestrator {

// The reference as a Markdown page: one table per section, the registered model names of this
// build (without plugins) under models.
std::string scenarioReference();

}  // namespace cosim::orchestrator
