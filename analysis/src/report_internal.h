// Pieces of the report shared between its source files. Private to cosim_analysis.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/report.h"

namespace cosim::analysis {

void writeRunTables(const RunAnalysis& a, const std::filesystem::path& dir);
void writeRunHtml(const RunAnalysis& a, const ReportOptions& o, const std::filesystem::path& dir,
                  const std::vector<std::string>& pngs, const std::string& plot_message);

Json comparisonJson(const std::vector<RunAnalysis>& runs, const std::vector<std::string>& folders);
void writeComparisonTables(const std::vector<RunAnalysis>& runs, const std::filesystem::path& dir);
void writeComparisonHtml(const std::vector<RunAnalysis>& runs, const std::vector<std::string>& folders,
                         const std::filesystem::path& dir, const std::vector<std::string>& pngs,
                         const std::string& plot_message);

// The zone-pass part of a run's report (report_passes.cpp): the analysis from zone_passes.csv
// (nullopt with `problem` saying why when the run has none), its report.json object, its CSV
// table and its HTML section.
std::optional<ZonePassReport> analyseZonePasses(const std::filesystem::path& run,
                                                const ParticleFile& file, const RunAnalysis& a,
                                                const ReportOptions& o, std::string& problem);
Json zonePassesJson(const RunAnalysis& a);
void writeZonePassTables(const RunAnalysis& a, const std::filesystem::path& dir);
std::string zonePassesHtml(const RunAnalysis& a);

// Scenario parameters (summary.json) present in every run with different values.
std::vector<std::string> variedParameters(const std::vector<RunAnalysis>& runs);
double parameter(const RunAnalysis& a, const std::string& name);

// PNG files (names) present in dir, sorted.
std::vector<std::string> pngsIn(const std::filesystem::path& dir);
std::string htmlEscape(const std::string& s);

}  // namespace cosim::analysis
