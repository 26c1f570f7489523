// `cosim study`: error against run time. Runs every combination of the varied settings, measures
// the scenario's observables and the wall time of each run, computes each observable's error
// against its analytic reference (or, without one, against the finest variant) and marks the
// Pareto front (no other variant both faster and more accurate). The running is here; the files
// (study.csv, study.json, study.md, the plot of error against run time) are written by
// analysis/src/report_study.cpp from one `analysis::StudyRecord`.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/study.h"
#include "cosim/util/stop_request.h"

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
  const util::StopRequest* stop = nullptr;  // Ctrl-C: the running variant stops, and the study
};

// "key=v1,v2,v3" -> (key, [v1, v2, v3]); throws std::runtime_error with the expected form.
std::pair<std::string, std::vector<std::string>> parseVary(const std::string& text);

// On the front iff no other point has cost <= and error <= with one of them strictly smaller.
std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error);

// study.json and the tables are written from this struct by the analysis library
// (cosim/analysis/study.h).
using analysis::StudyRecord;

int runStudy(const StudyOptions& options);

}  // namespace cosim::orchestrator
