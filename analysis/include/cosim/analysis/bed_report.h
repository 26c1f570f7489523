// The report of a run without coating (a fluidized bed, a settling bed, a spout): what the bed
// did over a window of the run, from the run's own records. timeseries.csv gives the pressure
// drop across the bed (its mean, its swing) and the parcel count; particles.h5 the bed's height
// (the parcel centres' median and 90th percentile per snapshot) and the parcels' speeds;
// summary.json the scene's observables against their references. `cosim report` writes it when
// the run has no coating_mass field (docs/analysis.md section 11).
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/summary.h"

namespace cosim::analysis {

// Mean, sample standard deviation, least and largest of the values in a window; n = 0: none.
struct WindowStatistics {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t n = 0;
  double mean = nan, sd = nan, min = nan, max = nan;
};
WindowStatistics statisticsOf(const std::vector<double>& values);
void to_json(Json& j, const WindowStatistics& s);  // null when n = 0

struct BedAnalysis {
  std::filesystem::path run;
  std::string label;
  std::optional<Summary> summary;  // summary.json, when the run has one
  double from = 0, to = 0;         // [s] the window analysed
  // timeseries.csv rows in the window (empty statistics when the column is not recorded)
  WindowStatistics pressure_drop;  // [Pa]
  WindowStatistics particle_count;
  // particles.h5 snapshots in the window: per snapshot a value, then their statistics
  std::size_t snapshots = 0;
  WindowStatistics height_median;  // [m] median height of the parcel centres
  WindowStatistics height_p90;     // [m] 90th percentile: the bed's top, splashes left out
  WindowStatistics speed_median;   // [m/s] median parcel speed (velocity recorded)
  std::vector<std::string> notes;  // what could not be analysed, and why
};

// The window: [from, to] when given (NaN: not given), else the second half of the record
// (a bed's start-up left out). Throws InputError naming the file when the run has neither
// timeseries.csv nor particles.h5 records in the window.
BedAnalysis analyseBed(const std::filesystem::path& run, double from, double to);

// report.json ("cosim-report", kind "bed") and report.md into `dir` (created).
Json toJson(const BedAnalysis& a);
std::string bedReportText(const BedAnalysis& a);

}  // namespace cosim::analysis
