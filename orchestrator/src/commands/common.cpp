#include <csignal>
#include <iostream>

#include "commands.h"
#include "coupler.h"
#include "participants.h"

namespace cosim::orchestrator {

namespace {
void onSignal(int sig) { processStop().request(sig); }
}  // namespace

const char* const kSetHelp =
    "override a value: key.path=value (e.g. coupling.end_time=0.5); a bare name sets a "
    "scenario parameter (e.g. flow_lpm=50); a YAML map or list replaces the whole node (e.g. "
    "'models.coating_zone={shape: sphere, center: [0, 0, 0.01], radius: 0.005}')";
const char* const kUnsetHelp =
    "remove a node (and everything below it) before the --set overrides, e.g. "
    "models.coating_zone";

util::StopRequest& processStop() {
  static util::StopRequest stop;
  return stop;
}

int reportRunEnd(const RunResult& r) {
  if (r.exit_code != 0) {
    std::cerr << "\ncosim: run stopped\n" << r.message << "\n";
    return r.exit_code;
  }
  for (const auto& v : r.observables) {
    if (!v.undefined.empty()) {
      std::cout << "cosim: " << v.name << ": no value (" << v.undefined << ")\n";
      continue;
    }
    std::cout << "cosim: " << v.name << " = " << v.value;
    if (v.reference)
      std::cout << " (reference " << *v.reference << ", relative error " << *v.relative_error
                << ")";
    std::cout << "\n";
  }
  std::cout << "cosim: results in " << r.folder.string() << "\n";
  return 0;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& x : names) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "(none)" : s;
}

void catchStopSignals(bool ignore_pipe) {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  if (ignore_pipe) std::signal(SIGPIPE, SIG_IGN);
}

void stopAtOnceOnSignals() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

}  // namespace cosim::orchestrator
