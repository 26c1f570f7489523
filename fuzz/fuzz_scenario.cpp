// Fuzzes the scenario loader: any text, as a scenario file, must give a Scenario or a
// ScenarioError, never a crash, a hang, undefined behaviour or another exception (an uncaught
// one aborts and counts as a crash). Seeds: the shipped scenes (scripts/fuzz.sh).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The first line may carry one --set (a line "#set KEY=VALUE"), so that overrides are fuzzed
  // with the file.
  std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> sets;
  if (text.rfind("#set ", 0) == 0) {
    const auto nl = text.find('\n');
    sets.push_back(text.substr(5, nl == std::string::npos ? std::string::npos : nl - 5));
  }
  try {
    // A folder without case files: files: and plugins: name nothing that exists.
    cosim::orchestrator::parseScenario(text, "/nonexistent-cosim-fuzz/scenario.yaml", sets);
  } catch (const cosim::orchestrator::ScenarioError&) {
  }
  return 0;
}
