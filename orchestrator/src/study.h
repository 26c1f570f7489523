// `cosim study`: error against run time. Runs every combination of the varied settings, measures
// the scenario's observables and the wall time of each run, computes each observable's error
// against its analytic reference (or, without one, against the finest variant), marks the Pareto
// front (no other variant both faster and more accurate), and writes study.csv, study.json,
// study.md and a plot of error against run time.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/files.h"

namespace cosim::orchestrator {

struct StudyOptions {
  std::filesystem::path scenario;
  std::vector<std::string> sets;                                       // fixed overrides
  std::vector<std::string> unsets;                                     // nodes removed
  std::vector<std::pair<std::string, std::vector<std::string>>> vary;  // key -> values
  std::filesystem::path output;                                        // study folder
  int finest = -1;  // variant used as reference where no analytic one exists; -1: the slowest
  bool quiet = false;
  bool plots = true;
  // false: a variant whose folder holds a completed run of exactly the same resolved scene is
  // read back, not run again (resume an interrupted study, or re-analyse with another --finest)
  bool rerun = false;
};

// "key=v1,v2,v3" -> (key, [v1, v2, v3]); throws std::runtime_error with the expected form.
std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text);

// On the front iff no other point has cost <= and error <= with one of them strictly smaller.
std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error);

// study.json: what was varied, the reference of each observable, and per variant its wall time,
// observables with their errors and whether it is on the Pareto front. Written and read through
// this struct (to_json / from_json with nlohmann-json).
struct StudyRecord {
  struct Observable {
    std::string name;
    double value = 0.0;           // NaN (written as null) when undefined
    std::optional<double> error;  // relative error against the reference, if there is one
  };
  struct Variant {
    std::string label;   // "key=value key=value"
    std::string folder;  // its run folder
    double wall_s = 0.0;
    bool ok = false;      // the run completed
    std::string message;  // why it failed (empty when ok)
    bool pareto = false;
    std::vector<Observable> observables;  // empty when the run failed
  };
  std::string scenario;                                         // the scenario file
  std::vector<std::string> vary;                                // the varied keys
  std::vector<std::pair<std::string, std::string>> references;  // observable -> its reference
  std::vector<Variant> variants;
};

void to_json(analysis::Json& j, const StudyRecord& s);
void from_json(const analysis::Json& j, StudyRecord& s);

int runStudy(const StudyOptions& options);

}  // namespace cosim::orchestrator
