// cosim batch RUN ... (the options and the work: ../batch_command.h)
#include <iostream>
#include <memory>

#include "../batch_command.h"
#include "commands.h"

namespace cosim::orchestrator {

void addBatchCommandLine(CLI::App& app, Commands& commands) {
  auto o = std::make_shared<BatchOptions>();
  auto* batch = addBatchCommand(app, *o);
  commands.push_back({batch, [o] { return runBatchCommand(*o, std::cout, std::cerr); }});
}

}  // namespace cosim::orchestrator
