#include "cosim/util/child_process.h"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "cosim/util/errors.h"

namespace cosim::util {

namespace fs = std::filesystem;

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const fs::path& cwd,
                           const fs::path& log, const std::map<std::string, std::string>& env,
                           const std::vector<int>& cpus)
    : log_(log) {
  if (argv.empty()) throw std::logic_error("empty command");
  // Everything the child needs is prepared before fork (no allocation after it).
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  cpu_set_t cpu_set;
  CPU_ZERO(&cpu_set);
  for (int c : cpus) CPU_SET(c, &cpu_set);
  const pid_t parent = getpid();
  int err_pipe[2];
  if (pipe2(err_pipe, O_CLOEXEC) != 0) throw ResourceError("pipe failed");
  pid_t pid = fork();
  if (pid < 0) throw ResourceError(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    close(err_pipe[0]);
    setpgid(0, 0);                     // own group: mpirun and its ranks are stopped together
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the parent
    if (getppid() != parent) _exit(127);
    signal(SIGINT, SIG_IGN);  // Ctrl-C goes to the parent, which stops us cleanly
    int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, STDIN_FILENO);
    if (chdir(cwd.c_str()) != 0) {
      int e = errno;
      (void)!write(err_pipe[1], &e, sizeof e);
      _exit(127);
    }
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
    // before exec: every thread the adapter starts inherits the binding
    if (!cpus.empty() && sched_setaffinity(0, sizeof cpu_set, &cpu_set) != 0) {
      int e = errno;
      (void)!write(err_pipe[1], &e, sizeof e);
      _exit(127);
    }
    execvp(args[0], args.data());
    int e = errno;
    (void)!write(err_pipe[1], &e, sizeof e);
    _exit(127);
  }
  close(err_pipe[1]);
  int child_errno = 0;
  ssize_t n = read(err_pipe[0], &child_errno, sizeof child_errno);
  close(err_pipe[0]);
  setpgid(pid, pid);  // also from the parent, to avoid the race
  pid_ = pid;
  reaped_ = false;
  if (n == sizeof child_errno) {
    waitpid(pid, nullptr, 0);
    reaped_ = true;
    pid_ = -1;
    throw ResourceError("cannot start '" + argv[0] + "': " + std::strerror(child_errno));
  }
}

ChildProcess& ChildProcess::operator=(ChildProcess&& o) noexcept {
  if (this != &o) {
    pid_ = o.pid_;
    reaped_ = o.reaped_;
    code_ = o.code_;
    exit_ = std::move(o.exit_);
    log_ = std::move(o.log_);
    o.pid_ = -1;
    o.reaped_ = true;
  }
  return *this;
}

ChildProcess::~ChildProcess() {
  if (!reaped_) stop(2.0);
}

void ChildProcess::reap(int status) {
  reaped_ = true;
  if (WIFEXITED(status)) {
    code_ = WEXITSTATUS(status);
    exit_ = "exited with code " + std::to_string(code_);
  } else if (WIFSIGNALED(status)) {
    code_ = 128 + WTERMSIG(status);
    exit_ = "killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
            strsignal(WTERMSIG(status)) + ")";
  }
  // Whatever the group leader left behind (e.g. MPI ranks) goes too.
  ::kill(-pid_, SIGKILL);
}

bool ChildProcess::running() {
  if (reaped_) return false;
  int status = 0;
  pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == 0) return true;
  if (r < 0) {
    reaped_ = true;
    exit_ = "vanished";
    code_ = -1;
    ::kill(-pid_, SIGKILL);
    return false;
  }
  reap(status);
  return false;
}

int ChildProcess::wait() {
  if (reaped_) return code_;
  int status = 0;
  pid_t r;
  do {
    r = waitpid(pid_, &status, 0);
  } while (r < 0 && errno == EINTR);
  if (r < 0) {
    reaped_ = true;
    exit_ = "vanished";
    code_ = -1;
    return code_;
  }
  reap(status);
  return code_;
}

void ChildProcess::stop(double grace) {
  if (reaped_) return;
  ::kill(-pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace);
  while (std::chrono::steady_clock::now() < deadline) {
    if (!running()) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(-pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  reaped_ = true;
  code_ = 128 + SIGKILL;
  exit_ = "stopped by the orchestrator";
}

int runProgram(const std::vector<std::string>& argv, const fs::path& log,
               const std::map<std::string, std::string>& env, const fs::path& cwd) {
  ChildProcess child(argv, cwd, log, env);
  return child.wait();
}

std::string displayCommand(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) {
    if (!out.empty()) out += ' ';
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789-_./=:,+@%") == std::string::npos;
    if (plain) {
      out += a;
      continue;
    }
    out += '\'';
    for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace cosim::util
