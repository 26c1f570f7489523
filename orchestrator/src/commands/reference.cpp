// cosim reference: every scenario key with its default and meaning (docs/scenario-reference.md)
#include "scenario/reference.h"

#include <iostream>

#include "commands.h"

namespace cosim::orchestrator {

void addReferenceCommand(CLI::App& app, Commands& commands) {
  auto* reference = app.add_subcommand(
      "reference",
      "Print every scenario key with its default and meaning, as Markdown (the page "
      "docs/scenario-reference.md is this output)");
  commands.push_back({reference, [] {
                        std::cout << scenarioReference();
                        return 0;
                      }});
}

}  // namespace cosim::orchestrator
