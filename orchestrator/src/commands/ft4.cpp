// cosim ft4 energy | calibrate (the options and the work: ../ft4_command.h)
#include <iostream>
#include <memory>

#include "../ft4_command.h"
#include "commands.h"

namespace cosim::orchestrator {

void addFt4Commands(CLI::App& app, Commands& commands) {
  auto o = std::make_shared<Ft4Options>();
  auto* ft4 = addFt4Command(app, *o);
  commands.push_back({ft4, [o, ft4] { return runFt4Command(*ft4, *o, std::cout, std::cerr); }});
}

}  // namespace cosim::orchestrator
