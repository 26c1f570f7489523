// TimeSeriesRecorder: run_dir/timeseries.csv, one row per coupling step, flushed every row so a
// crash keeps every finished step. First column is always "time" [s]; the others are named by
// the caller. readTimeSeries() loads such a file back for the report.
//
// Columns the report uses (write them with these names; see docs/analysis.md). Amounts are
// CUMULATIVE since the start of the run, so a row is meaningful on its own:
//   precursor_in       [kg] precursor through the inlets so far
//   precursor_out      [kg] precursor through the outlets so far
//   precursor_held     [kg] precursor in the gas now
//   precursor_removed  [kg] precursor taken from the gas by the coating sink so far
//   coated_mass        [kg] coating credited to the particles so far
//   wall_seconds       [s]  wall-clock time since the run started
//   pressure_drop      [Pa] inlet average minus outlet average pressure over the last step
// Mass balance (mass_balance.h): in - out - (held - held at start) = coated_mass. A row with
// in = out = 0 first is read as the initial state. Because the coating removed in step k is
// credited to the particles in step k+1, the orchestrator writes one more row after its final
// credit (same time as the last step) so the last row holds all of it.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace cosim::analysis {

inline constexpr const char* kTimeSeriesFile = "timeseries.csv";

namespace column {
inline constexpr const char* time = "time";
inline constexpr const char* precursor_in = "precursor_in";
inline constexpr const char* precursor_out = "precursor_out";
inline constexpr const char* precursor_held = "precursor_held";
inline constexpr const char* precursor_removed = "precursor_removed";
inline constexpr const char* coated_mass = "coated_mass";
inline constexpr const char* particle_count = "particle_count";
inline constexpr const char* wall_seconds = "wall_seconds";
inline constexpr const char* pressure_drop = "pressure_drop";  // [Pa] inlets minus outlets
}  // namespace column

class TimeSeriesRecorder {
 public:
  enum class Mode { create, append };
  // columns: names after "time". Throws std::runtime_error naming the file on failure; in
  // append mode the existing header must match.
  TimeSeriesRecorder(const std::filesystem::path& path, std::vector<std::string> columns,
                     Mode mode = Mode::create);
  ~TimeSeriesRecorder();
  TimeSeriesRecorder(const TimeSeriesRecorder&) = delete;
  TimeSeriesRecorder& operator=(const TimeSeriesRecorder&) = delete;

  // One row; values.size() must equal the number of columns. Flushed before returning.
  void write(double time, const std::vector<double>& values);
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
};

struct TimeSeries {
  std::vector<std::string> columns;         // including "time" first
  std::vector<std::vector<double>> values;  // values[c][row]
  bool has(const std::string& name) const;
  // Column by name; throws std::runtime_error naming the file and the column if absent.
  const std::vector<double>& at(const std::string& name) const;
  std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
  std::string source;
};

// Reads a CSV written by TimeSeriesRecorder (header line, then numbers; "nan" allowed). A last
// line cut short by a crash is ignored. Throws with file:line on malformed content.
TimeSeries readTimeSeries(const std::filesystem::path& path);

// Resume: keeps the header and the first `rows` rows of a time-series file (replaced atomically);
// throws std::runtime_error naming the file if it has fewer rows.
void truncateTimeSeries(const std::filesystem::path& path, std::size_t rows);

}  // namespace cosim::analysis
