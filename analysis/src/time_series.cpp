#include "cosim/analysis/time_series.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    out.push_back(cell);
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string header(const std::vector<std::string>& columns) {
  std::string h = column::time;
  for (const auto& c : columns) h += "," + c;
  return h;
}
}  // namespace

TimeSeriesRecorder::TimeSeriesRecorder(const std::filesystem::path& path,
                                       std::vector<std::string> columns, Mode mode)
    : path_(path), columns_(std::move(columns)) {
  for (const auto& c : columns_) {
    if (c.empty() || c.find_first_of(",\n\r\"") != std::string::npos || c == column::time) {
      throw std::logic_error(
          "TimeSeriesRecorder: column name '" + c + "' for " + path.string() +
          " is not allowed (empty, 'time', or containing a comma, quote or newline)");
    }
  }
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
  }
  const std::string h = header(columns_);
  if (mode == Mode::append && std::filesystem::exists(path) &&
      std::filesystem::file_size(path) > 0) {
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    if (!first.empty() && first.back() == '\r') first.pop_back();
    if (first != h) {
      throw InputError(path.string() + " has columns '" + first + "' but this run writes '" + h +
                       "': use a new run folder");
    }
    file_ = std::fopen(path.c_str(), "a");
  } else {
    file_ = std::fopen(path.c_str(), "w");
    if (file_ != nullptr) {
      std::fprintf(file_, "%s\n", h.c_str());
      std::fflush(file_);
    }
  }
  if (file_ == nullptr) {
    const int err = errno;
    throw Error(kindOfErrno(err), "cannot write " + path.string() + ": " + std::strerror(err));
  }
}

TimeSeriesRecorder::~TimeSeriesRecorder() {
  if (file_ != nullptr) std::fclose(file_);
}

void TimeSeriesRecorder::write(double time, const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    throw std::runtime_error("TimeSeriesRecorder: " + std::to_string(values.size()) +
                             " values for " + std::to_string(columns_.size()) + " columns (" +
                             header(columns_) + ") in " + path_.string());
  }
  std::string row = formatShortest(time);
  for (double v : values) {
    row += ',';
    row += formatShortest(v);
  }
  row += '\n';
  if (std::fputs(row.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    const int err = errno;
    throw Error(kindOfErrno(err), "writing " + path_.string() + " failed: " + std::strerror(err));
  }
}

bool TimeSeries::has(const std::string& name) const {
  for (const auto& c : columns) {
    if (c == name) return true;
  }
  return false;
}

const std::vector<double>& TimeSeries::at(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return values[i];
  }
  std::string have;
  for (const auto& c : columns) have += (have.empty() ? "" : ", ") + c;
  throw InputError(source + " has no column '" + name + "' (columns: " + have + ")");
}

TimeSeries readTimeSeries(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    throw InputError(path.string() +
                     " cannot be read: the run wrote no time series "
                     "(did it complete a coupling step?)");
  }
  TimeSeries ts;
  ts.source = path.string();
  std::string line;
  if (!std::getline(in, line))
    throw InputError(path.string() + " is empty (expected a header line 'time,...')");
  ts.columns = splitCsv(line);
  if (ts.columns.empty() || ts.columns.front() != column::time) {
    throw InputError(path.string() + ":1: header must start with 'time', found '" + line + "'");
  }
  ts.values.assign(ts.columns.size(), {});
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  // A file cut by a crash may end in a partial line without its newline: std::getline still
  // returns it; drop a last line with too few cells.
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& l = lines[i];
    if (l.empty() || l == "\r") continue;
    auto cells = splitCsv(l);
    if (cells.size() != ts.columns.size()) {
      if (i + 1 == lines.size()) break;
      throw InputError(path.string() + ":" + std::to_string(i + 2) + ": " +
                       std::to_string(cells.size()) + " values, header has " +
                       std::to_string(ts.columns.size()));
    }
    std::vector<double> row;
    bool ok = true;
    for (const auto& c : cells) {
      char* end = nullptr;
      const double v = std::strtod(c.c_str(), &end);
      if (c.empty() || end == nullptr || *end != '\0') {
        ok = false;
        break;
      }
      row.push_back(v);
    }
    if (!ok) {
      if (i + 1 == lines.size()) break;
      throw InputError(path.string() + ":" + std::to_string(i + 2) + ": not a number in '" + l +
                       "'");
    }
    for (std::size_t c = 0; c < row.size(); ++c) ts.values[c].push_back(row[c]);
  }
  return ts;
}

void truncateTimeSeries(const std::filesystem::path& path, std::size_t rows) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open it to cut it back");
  std::string text, line;
  std::size_t kept = 0;
  if (std::getline(in, line)) text += line + "\n";  // header
  while (kept < rows && std::getline(in, line)) {
    text += line + "\n";
    ++kept;
  }
  if (kept < rows) {
    throw InputError(path.string() + " has " + std::to_string(kept) + " rows, fewer than the " +
                     std::to_string(rows) +
                     " the checkpoint recorded: the run folder was changed after it");
  }
  writeFileAtomically(path, text);
}

}  // namespace cosim::analysis
