#include "adapter_check.h"

#include <fmt/format.h>
#include <stdlib.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "case_files.h"
#include "participants.h"
#include "processes.h"
#include "scenario/participants_section.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

namespace {

// A private temporary folder, removed with everything in it when the check ends.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (fs::temp_directory_path() / "cosim-validate-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw ScenarioError("cosim validate: cannot create a temporary folder in " +
                          fs::temp_directory_path().string() + " to check the adapters");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  const auto b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::string textOf(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::vector<std::string> checkAdapters(const Scenario& sc, const Plan& plan, double timeout_s) {
  std::vector<std::string> lines;
  TemporaryFolder tmp;
  for (const auto& [name, spec] : sc.participants) {
    const bool used = name == "particles" || (name == "fluid" && plan.fluid);
    if (!used) continue;
    const std::string where = sc.file.string() + ": participants." + name;
    if (!knownAdapters().count(spec.adapter)) {
      lines.push_back(name + ": options not checked (custom adapter '" + spec.adapter +
                      "'; it checks them when the run starts)");
      continue;
    }
    const auto exe = findExecutable(spec.command);
    if (!exe) {
      throw ScenarioError(where + ".adapter: cannot find the executable '" + spec.command +
                          "' of adapter '" + spec.adapter +
                          "' (looked next to cosim and in PATH; was it built?)");
    }
    const fs::path workdir = tmp.path() / name;
    fs::create_directories(workdir);
    if (!spec.files.empty()) {
      try {
        copyCaseFiles(spec.files, workdir, sc.parameters);
      } catch (const std::exception& e) {
        throw ScenarioError(where + ".files: " + e.what());
      }
    }
    const fs::path welcome = tmp.path() / (name + ".welcome");
    {
      std::ofstream out(welcome, std::ios::binary);
      out << welcomeFor(sc, plan, spec, workdir, fs::path()).SerializeAsString();
      if (!out.flush())
        throw ScenarioError("cosim validate: cannot write " + welcome.string() +
                            " to check the adapters (disk full?)");
    }
    const fs::path log = tmp.path() / (name + ".check.log");
    util::ChildProcess child(
        {exe->string(), "--check-options", welcome.string(), "--ranks", std::to_string(spec.mpi)},
        workdir, log, {});
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (child.running()) {
      if (std::chrono::steady_clock::now() > deadline) {
        child.stop(1.0);
        throw ScenarioError(where + ": adapter '" + spec.adapter + "' (" + exe->string() +
                            ") did not answer --check-options within " +
                            fmt::format("{:g}", timeout_s) +
                            " s; is it a cosim adapter of this version?");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    // The adapter saw the templated copy; the user knows the folder it came from
    std::string said = trimmed(textOf(log));
    const std::string copy = workdir.string();
    const std::string origin =
        spec.files.empty() ? std::string("the participant's folder") : spec.files.string();
    for (auto at = said.find(copy); at != std::string::npos; at = said.find(copy, at))
      said.replace(at, copy.size(), origin), at += origin.size();
    if (child.exitCode() != 0) {
      // the settings may be the command line's rather than the file's: say which
      std::string given;
      for (const auto& o : sc.overrides) {
        if (o.rfind("participants." + name + ".", 0) == 0 ||
            o.rfind("participants." + name + "=", 0) == 0)
          given += (given.empty() ? "" : ", ") + std::string("--set ") + o;
      }
      throw ScenarioError(where + ": adapter '" + spec.adapter + "' refuses the scene (" +
                          child.exitDescription() + "):\n  " +
                          (said.empty() ? std::string("(it said nothing)") : said) +
                          (given.empty() ? std::string()
                                         : "\n  (this participant's settings include the command "
                                           "line's " +
                                               given + ")"));
    }
    lines.push_back(name + ": adapter '" + spec.adapter + "' accepts the options and files" +
                    (spec.mpi > 1 ? " on " + std::to_string(spec.mpi) + " MPI ranks" : ""));
  }
  return lines;
}

}  // namespace cosim::orchestrator
