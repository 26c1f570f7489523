// What the report tests share: a fresh scratch folder, a file's text, and `cosim report` run as
// the tests run it (no plots: matplotlib has tests of its own; the log kept to show on failure).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/report.h"

namespace cosim::analysis::test {

// An empty folder `name` in this test process's scratch folder for `suite`.
inline std::filesystem::path scratchFolder(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / (suite + "-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `cosim report` on `runs` without plots; `options` may be changed before run().
struct QuietReport {
  ReportOptions options;
  std::ostringstream log;

  explicit QuietReport(std::vector<std::filesystem::path> runs) {
    options.runs = std::move(runs);
    options.plots = false;
    options.log = &log;
  }
  QuietReport(const QuietReport&) = delete;
  QuietReport& operator=(const QuietReport&) = delete;

  int run() { return runReport(options); }
};

}  // namespace cosim::analysis::test
