// Finding and running scripts/plot_report.py (matplotlib, Agg backend).
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cosim/analysis/report.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''";
    else q += c;
  }
  return q + "'";
}

std::filesystem::path executableDir() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

int run(const std::string& command) {
  const int rc = std::system(command.c_str());
  if (rc == -1) return -1;
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : 128;
}

std::string tail(const std::filesystem::path& file, std::size_t lines) {
  std::ifstream in(file);
  std::vector<std::string> all;
  for (std::string l; std::getline(in, l);) all.push_back(l);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += all[i] + "\n";
  return out;
}
}  // namespace

std::optional<std::filesystem::path> findPlotScript() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("COSIM_SCRIPTS"); env != nullptr && *env != '\0') {
    candidates.emplace_back(std::filesystem::path(env) / "plot_report.py");
  }
  const auto exe = executableDir();
  if (!exe.empty()) {
    candidates.push_back(exe / ".." / "share" / "cosim" / "scripts" / "plot_report.py");
    candidates.push_back(exe / ".." / ".." / "scripts" / "plot_report.py");
  }
  candidates.emplace_back(std::filesystem::path(COSIM_SOURCE_SCRIPTS_DIR) / "plot_report.py");
  for (const auto& c : candidates) {
    if (std::filesystem::is_regular_file(c)) return c.lexically_normal();
  }
  return std::nullopt;
}

std::optional<std::string> findPython(std::string& why_not) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("COSIM_PYTHON"); env != nullptr && *env != '\0') {
    candidates.emplace_back(env);  // the user's explicit choice: no fallback behind their back
  } else {
    candidates.emplace_back("python3");
    candidates.emplace_back("/usr/bin/python3");
  }
  for (const auto& py : candidates) {
    if (run(shellQuote(py) + " -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0) return py;
  }
  why_not = "no python3 with matplotlib and numpy found (tried";
  for (const auto& c : candidates) why_not += " " + c;
  why_not += "): install them with `sudo apt-get install python3-matplotlib python3-numpy`, or set "
             "COSIM_PYTHON to a python3 that has them, then run `cosim report` again";
  return std::nullopt;
}

bool drawPlots(const std::filesystem::path& folder, std::string& message) {
  auto script = findPlotScript();
  if (!script) {
    message = "plot_report.py not found: set COSIM_SCRIPTS to the folder holding it (the source tree's scripts/)";
    return false;
  }
  auto python = findPython(message);
  if (!python) return false;
  const auto log = folder / "plot_report.log";
  const std::string cmd = "MPLBACKEND=Agg " + shellQuote(*python) + " " + shellQuote(script->string()) + " " +
                          shellQuote(folder.string()) + " > " + shellQuote(log.string()) + " 2>&1";
  const int rc = run(cmd);
  if (rc != 0) {
    message = script->string() + " failed (exit " + std::to_string(rc) + "); its output is in " + log.string() +
              ":\n" + tail(log, 15);
    return false;
  }
  return true;
}

std::vector<std::string> pngsIn(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.is_regular_file() && e.path().extension() == ".png") out.push_back(e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace cosim::analysis
