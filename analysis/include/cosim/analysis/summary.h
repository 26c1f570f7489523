// run_dir/summary.json: the headline numbers and timings of a run, written atomically (a reader
// never sees half a file), so the orchestrator can rewrite it as the run progresses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/json.h"

namespace cosim::analysis {

inline constexpr const char* kSummaryFile = "summary.json";

struct Summary {
  std::string scenario;        // scenario name
  std::string run_id;
  std::string status;          // "running", "completed", "failed", "interrupted"
  std::string message;         // error text when failed, else empty
  double start_time = 0;       // [s] simulated
  double end_time = 0;         // [s] simulated, reached so far
  std::int64_t steps = 0;      // coupling steps done
  // Headline numbers, name -> value in SI units; put the unit in the name (e.g.
  // "coated_mass_kg", "mass_balance_error_percent").
  std::vector<std::pair<std::string, double>> headline;
  // Wall-clock seconds per phase (e.g. "total", "fluid", "particles", "models", "exchange").
  std::vector<std::pair<std::string, double>> timings;
  Json extra;                  // anything else (e.g. the parameters of the run); null = none
};

Json toJson(const Summary& s);
// Writes the JSON (atomically). Throws std::runtime_error naming the path on failure.
void writeSummary(const std::filesystem::path& path, const Summary& summary);

}  // namespace cosim::analysis
