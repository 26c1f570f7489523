#include "cosim/analysis/zone_pass_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/analysis/time_series.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {

constexpr const char* kHeader = "parcel_id,entry_time,exit_time,coating_kg,entry,exit";

const char* exitName(ZonePass::Exit e) {
  switch (e) {
    case ZonePass::Exit::left:
      return "left";
    case ZonePass::Exit::run_end:
      return "run_end";
    case ZonePass::Exit::deleted:
      return "deleted";
  }
  return "left";
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string c; std::getline(s, c, ',');) {
    while (!c.empty() && (c.back() == '\r' || c.back() == ' ')) c.pop_back();
    out.push_back(c);
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

bool number(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end != nullptr && *end == '\0';
}

}  // namespace

ZonePassWriter::ZonePassWriter(const std::filesystem::path& path, Mode mode) : path_(path) {
  if (mode == Mode::append && std::filesystem::exists(path) &&
      std::filesystem::file_size(path) > 0) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line != kHeader) {
      throw InputError(path.string() + " has columns '" + line + "', expected '" + kHeader +
                       "': it was not written by this cosim; use a new run folder");
    }
    while (std::getline(in, line)) rows_ += line.empty() ? 0 : 1;
    file_ = std::fopen(path.c_str(), "a");
  } else {
    file_ = std::fopen(path.c_str(), "w");
    if (file_ != nullptr) {
      std::fprintf(file_, "%s\n", kHeader);
      std::fflush(file_);
    }
  }
  if (file_ == nullptr) {
    const int err = errno;
    throw Error(kindOfErrno(err), "cannot write " + path.string() + ": " + std::strerror(err));
  }
}

ZonePassWriter::~ZonePassWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void ZonePassWriter::write(const std::vector<ZonePass>& passes) {
  if (passes.empty()) return;
  std::string text;
  for (const auto& p : passes) {
    text += fmt::format("{},{},{},{},{},{}\n", p.parcel_id, formatShortest(p.entry_time),
                        formatShortest(p.exit_time), formatShortest(p.coating),
                        p.at_start ? "at_start" : "entered", exitName(p.exit));
  }
  if (std::fputs(text.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    const int err = errno;
    throw Error(kindOfErrno(err), "writing " + path_.string() + " failed: " + std::strerror(err));
  }
  rows_ += passes.size();
}

std::vector<ZonePass> readZonePasses(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + " cannot be read");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path.string() + " is empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != kHeader) {
    throw InputError(path.string() + ":1: header '" + line + "', expected '" + kHeader + "'");
  }
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  std::vector<ZonePass> out;
  out.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].empty() || lines[i] == "\r") continue;
    const bool last = i + 1 == lines.size();
    const std::string where = path.string() + ":" + std::to_string(i + 2) + ": ";
    const auto c = cells(lines[i]);
    ZonePass p;
    double id = 0;
    bool ok = c.size() == 6 && number(c[0], id) && number(c[1], p.entry_time) &&
              number(c[2], p.exit_time) && number(c[3], p.coating);
    if (ok) {
      p.parcel_id = static_cast<std::int64_t>(id);
      ok = c[4] == "entered" || c[4] == "at_start";
      p.at_start = c[4] == "at_start";
      if (c[5] == "left")
        p.exit = ZonePass::Exit::left;
      else if (c[5] == "run_end")
        p.exit = ZonePass::Exit::run_end;
      else if (c[5] == "deleted")
        p.exit = ZonePass::Exit::deleted;
      else
        ok = false;
    }
    if (!ok) {
      if (last) break;  // cut short by a crash
      throw InputError(where +
                       "expected parcel_id,entry_time,exit_time,coating_kg,"
                       "entered|at_start,left|run_end|deleted; found '" +
                       lines[i] + "'");
    }
    if (!(p.exit_time >= p.entry_time)) {
      throw InputError(where + "exit_time " + c[2] + " is before entry_time " + c[1]);
    }
    out.push_back(p);
  }
  return out;
}

void truncateZonePasses(const std::filesystem::path& path, std::size_t rows) {
  truncateTimeSeries(path, rows);  // the same: a header line and rows
}

}  // namespace cosim::analysis
