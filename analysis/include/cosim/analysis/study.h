// The files of a `cosim study` (the variants are run by the orchestrator, orchestrator/src/
// study.cpp): study.json, study.csv and study.md, and the plot of error against run time
// (scripts/plot_study.py -> error_vs_runtime.png). All are written from one struct,
// `StudyRecord`, which is also what study.json reads back into (to_json / from_json with
// nlohmann-json).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/files.h"

namespace cosim::analysis {

// study.json: what was varied, the reference of each observable, and per variant its varied
// values, wall time, observables with their reference and error, and whether it is on the
// Pareto front.
struct StudyRecord {
  struct Observable {
    std::string name;
    double value = 0.0;               // NaN (written as null) when undefined
    std::optional<double> reference;  // the value it is compared with, if there is one
    std::optional<double> error;      // relative error against the reference, if there is one
  };
  struct Variant {
    std::string label;                // "key=value key=value"
    std::vector<std::string> values;  // the varied values, in the order of StudyRecord::vary
    std::string folder;               // its run folder
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

void to_json(Json& j, const StudyRecord& s);
void from_json(const Json& j, StudyRecord& s);

// study.csv (one row per variant, full precision), study.json and study.md (the table for
// docs/) into folder. Throws std::runtime_error naming the file on failure.
void writeStudyFiles(const std::filesystem::path& folder, const StudyRecord& study);

// The Markdown table of study.md.
std::string studyMarkdown(const StudyRecord& study);

// Draws error_vs_runtime.png in folder with scripts/plot_study.py (from study.json; its output
// in plot_study.log). Returns false with message saying why when it was not drawn.
bool drawStudyPlot(const std::filesystem::path& folder, std::string& message);

}  // namespace cosim::analysis
