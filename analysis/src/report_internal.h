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

// A run's label in tables and plots: its folder's name.
std::string runLabel(const std::filesystem::path& run);

void writeRunTables(const RunAnalysis& a, const std::filesystem::path& dir);
void writeRunHtml(const RunAnalysis& a, const ReportOptions& o, const std::filesystem::path& dir,
                  const std::vector<std::string>& pngs, const std::string& plot_message);

Json comparisonJson(const std::vector<RunAnalysis>& runs, const std::vector<std::string>& folders,
                    const ReportOptions& o);
// The report.json objects of the operating conditions and of the display units.
Json conditionsJson(const OperatingConditions& c);
Json unitsJson(const RunAnalysis& a);
void writeComparisonTables(const std::vector<RunAnalysis>& runs, const std::filesystem::path& dir);
void writeComparisonHtml(const std::vector<RunAnalysis>& runs,
                         const std::vector<std::string>& folders, const ReportOptions& o,
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

// The whole batch by the long-time model (report_batch.cpp): computed from the run's snapshots,
// its report.json object and its HTML section.
std::optional<BatchPrediction> analyseBatch(const ParticleFile& file, const ReportOptions& o,
                                            std::string& problem);
Json batchJson(const RunAnalysis& a);
std::string batchHtml(const RunAnalysis& a);

// Scenario parameters (summary.json) present in every run with different values.
std::vector<std::string> variedParameters(const std::vector<RunAnalysis>& runs);
double parameter(const RunAnalysis& a, const std::string& name);

// The verdict in words (report_verdict.cpp): one or two sentences for the top of a page, the
// short form for a table ("well mixed", "poorly mixed", ...), and the batch times it speaks of
// (the last --predict time and predict_until, in seconds of coating) as "20-60 min".
struct VerdictText {
  std::string head;  // "Well mixed", "Poorly mixed", "Well mixed only under relaxed criteria"
  std::string body;  // the rest: what was seen, and what it means for a batch
};
VerdictText verdictText(const RunAnalysis& a, const ReportOptions& o);
std::string plainVerdict(const RunAnalysis& a, const ReportOptions& o);  // head + ": " + body
std::string shortVerdict(const MixingVerdict& v);
std::vector<double> batchTimes(const ReportOptions& o);
std::string batchRange(const ReportOptions& o);

// PNG files (names) present in dir, sorted.
std::vector<std::string> pngsIn(const std::filesystem::path& dir);
std::string htmlEscape(const std::string& s);

}  // namespace cosim::analysis
