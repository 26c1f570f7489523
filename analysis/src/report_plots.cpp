// Finding and running scripts/plot_report.py (matplotlib, Agg backend).
#include <algorithm>
#include <cstdlib>
#include <map>
#include <vector>

#include "cosim/analysis/report.h"
#include "cosim/util/child_process.h"
#include "cosim/util/text_file.h"
#include "report_internal.h"

namespace cosim::analysis {

namespace {
std::filesystem::path executableDir() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

// Runs a program from its argument vector (no shell); -1 if it cannot be started.
int run(const std::vector<std::string>& argv, const std::filesystem::path& log,
        const std::map<std::string, std::string>& env = {}) {
  try {
    return util::runProgram(argv, log, env);
  } catch (const std::exception&) {
    return -1;
  }
}
}  // namespace

std::optional<std::filesystem::path> findScript(const std::string& name) {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("COSIM_SCRIPTS"); env != nullptr && *env != '\0') {
    candidates.emplace_back(std::filesystem::path(env) / name);
  }
  const auto exe = executableDir();
  if (!exe.empty()) {
    candidates.push_back(exe / ".." / "share" / "cosim" / "scripts" / name);
    candidates.push_back(exe / ".." / ".." / "scripts" / name);
  }
  candidates.emplace_back(std::filesystem::path(COSIM_SOURCE_SCRIPTS_DIR) / name);
  for (const auto& c : candidates) {
    if (std::filesystem::is_regular_file(c)) return c.lexically_normal();
  }
  return std::nullopt;
}

std::optional<std::filesystem::path> findPlotScript() { return findScript("plot_report.py"); }

std::optional<std::string> findPython(std::string& why_not) {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("COSIM_PYTHON"); env != nullptr && *env != '\0') {
    candidates.emplace_back(env);  // the user's explicit choice: no fallback behind their back
  } else {
    candidates.emplace_back("python3");
    candidates.emplace_back("/usr/bin/python3");
  }
  for (const auto& py : candidates) {
    if (run({py, "-c", "import matplotlib, numpy"}, "/dev/null") == 0) return py;
  }
  why_not = "no python3 with matplotlib and numpy found (tried";
  for (const auto& c : candidates) why_not += " " + c;
  why_not +=
      "): install them with `sudo apt-get install python3-matplotlib python3-numpy`, or set "
      "COSIM_PYTHON to a python3 that has them, then run the command again";
  return std::nullopt;
}

bool runPlotScript(const std::string& name, const std::filesystem::path& folder,
                   const std::filesystem::path& log, std::string& message) {
  return runPlotScript(name, std::vector<std::string>{folder.string()}, log, message);
}

bool runPlotScript(const std::string& name, const std::vector<std::string>& args,
                   const std::filesystem::path& log, std::string& message) {
  auto script = findScript(name);
  if (!script) {
    message = name +
              " not found: set COSIM_SCRIPTS to the folder holding it (the source tree's scripts/)";
    return false;
  }
  auto python = findPython(message);
  if (!python) return false;
  std::error_code ec;
  std::filesystem::remove(log, ec);  // the log of this drawing only
  std::vector<std::string> argv{*python, script->string()};
  argv.insert(argv.end(), args.begin(), args.end());
  const int rc = run(argv, log, {{"MPLBACKEND", "Agg"}});
  if (rc != 0) {
    message = script->string() + " failed (exit " + std::to_string(rc) + "); its output is in " +
              log.string() + ":\n" + util::tailOfFile(log, 15);
    return false;
  }
  return true;
}

std::string drawFigure(const std::string& script, const std::vector<std::string>& args,
                       const std::filesystem::path& png, const std::filesystem::path& log) {
  std::string why;
  if (!runPlotScript(script, args, log, why)) return "no plot: " + why;
  std::error_code ec;
  std::filesystem::remove(log, ec);
  return "plot: " + png.string();
}

bool drawPlots(const std::filesystem::path& folder, std::string& message) {
  return runPlotScript("plot_report.py", folder, folder / "plot_report.log", message);
}

std::vector<std::string> pngsIn(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.is_regular_file() && e.path().extension() == ".png")
      out.push_back(e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace cosim::analysis
