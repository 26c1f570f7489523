// run_dir/summary.json: the status, headline numbers, settings, observables and timings of a run.
// Written and read through one struct (to_json / from_json with nlohmann-json), atomically (a
// reader never sees half a file), so the orchestrator can rewrite it as the run progresses and
// `cosim report` and `cosim study` read back exactly what it wrote.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/files.h"

namespace cosim::analysis {

inline constexpr const char* kSummaryFile = "summary.json";

// One of the scenario's observables as measured at the end of the run.
struct ObservableValue {
  std::string name;
  double value = 0.0;     // NaN when undefined
  std::string undefined;  // why there is no value (empty when there is one)
  std::optional<double> reference;
  // |value - reference| / |reference| (absolute error if the reference is 0).
  std::optional<double> relative_error;
};

struct Summary {
  std::string scenario;  // scenario name
  std::string run_id;
  std::string status;      // "running", "completed", "failed", "interrupted"
  std::string message;     // error text when failed, else empty
  double start_time = 0;   // [s] simulated
  double end_time = 0;     // [s] simulated, reached so far
  std::int64_t steps = 0;  // coupling steps done
  // Headline numbers, name -> value in SI units; put the unit in the name (e.g.
  // "coated_mass_kg", "mass_balance_error_percent"). NaN is written as null.
  std::vector<std::pair<std::string, double>> headline;
  // Wall-clock seconds per phase (e.g. "total", "fluid", "particles", "models", "exchange").
  std::vector<std::pair<std::string, double>> timings;
  // The run's settings and results beyond the headline (the "extra" object of the file).
  std::vector<std::pair<std::string, double>> parameters;  // scenario parameters
  double coupling_dt = 0;                                  // [s]
  std::int64_t dem_steps = 0;                              // DEM steps per coupling step
  double cg = 1;                                           // coarse-graining factor
  bool coating = false;                                    // the scene has mass transfer
  std::vector<ObservableValue> observables;
};

void to_json(Json& j, const Summary& s);
// Throws nlohmann::json::exception when a required key is missing or has the wrong type.
void from_json(const Json& j, Summary& s);

// Writes the JSON atomically. When that fails (no room for the second copy: disk full) and the
// file exists (the orchestrator writes one with status "running" when a run starts), it is
// written over the old one in place, whose space it takes. Throws std::runtime_error naming
// the path and the reason when neither works.
void writeSummary(const std::filesystem::path& path, const Summary& summary);
// Reads it back. Throws std::runtime_error naming the path when it cannot be read, is not JSON,
// or is not a summary.
Summary readSummary(const std::filesystem::path& path);

}  // namespace cosim::analysis
