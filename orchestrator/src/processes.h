// Participant processes: started in their own process group with their output in a log file,
// watched without blocking, stopped as a group (mpirun and all its ranks) and never orphaned
// (each child dies with the orchestrator, PR_SET_PDEATHSIG).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cosim::orchestrator {

class ChildProcess {
 public:
  ChildProcess() = default;
  // Throws std::runtime_error if the executable cannot be started.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
               const std::filesystem::path& log, const std::map<std::string, std::string>& env);
  ChildProcess(ChildProcess&& o) noexcept { *this = std::move(o); }
  ChildProcess& operator=(ChildProcess&& o) noexcept;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  bool running();  // reaps it if it has exited
  // How it ended, e.g. "exited with code 1" or "killed by signal 9 (Killed)"; empty if running.
  std::string exitDescription() const { return exit_; }
  int exitCode() const { return code_; }
  // SIGTERM to the group, wait up to grace seconds, then SIGKILL. Reaps the child.
  void stop(double grace_seconds);
  const std::filesystem::path& log() const { return log_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = true;
  int code_ = 0;
  std::string exit_;
  std::filesystem::path log_;
};

// Last n lines of a text file (for error messages).
std::string tailOfFile(const std::filesystem::path& file, int lines);

// Finds an executable: absolute/relative path as given, next to the running cosim, or in PATH.
std::optional<std::filesystem::path> findExecutable(const std::string& name);

}  // namespace cosim::orchestrator
