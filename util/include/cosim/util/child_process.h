// Child processes started from an argument vector (fork + execvp: no shell ever sees the
// arguments, so no text of a scenario can become a command). A child runs in its own process
// group with its output in a log file, is watched without blocking, stopped as a group (mpirun
// and all its ranks) and never orphaned (it dies with its parent, PR_SET_PDEATHSIG).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cosim::util {

class ChildProcess {
 public:
  ChildProcess() = default;
  // argv[0] is looked up in PATH unless it holds a '/'. stdout and stderr are appended to `log`
  // (e.g. /dev/null), stdin is /dev/null; `env` is added to the inherited environment.
  // `cpus`: the CPUs the child and all its threads run on (empty: wherever the system puts them).
  // Throws cosim::ResourceError if the executable cannot be started (no fork, no exec).
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
               const std::filesystem::path& log, const std::map<std::string, std::string>& env,
               const std::vector<int>& cpus = {});
  ChildProcess(ChildProcess&& o) noexcept { *this = std::move(o); }
  ChildProcess& operator=(ChildProcess&& o) noexcept;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  bool running();  // reaps it if it has exited
  // How it ended, e.g. "exited with code 1" or "killed by signal 9 (Killed)"; empty if running.
  std::string exitDescription() const { return exit_; }
  // Exit code, or 128 + signal number.
  int exitCode() const { return code_; }
  // Blocks until the child exits; returns exitCode().
  int wait();
  // SIGTERM to the group, wait up to grace seconds, then SIGKILL. Reaps the child.
  void stop(double grace_seconds);
  const std::filesystem::path& log() const { return log_; }

 private:
  void reap(int status);
  pid_t pid_ = -1;
  bool reaped_ = true;
  int code_ = 0;
  std::string exit_;
  std::filesystem::path log_;
};

// Runs a program to completion in `cwd` with its output appended to `log` and returns its exit
// code (128 + signal if killed). Throws cosim::ResourceError if it cannot be started.
int runProgram(const std::vector<std::string>& argv, const std::filesystem::path& log,
               const std::map<std::string, std::string>& env = {},
               const std::filesystem::path& cwd = ".");

// A command line shown to a person (log lines, error messages), arguments single-quoted where
// needed. For reading only: programs are always started from the argument vector.
std::string displayCommand(const std::vector<std::string>& argv);

}  // namespace cosim::util
