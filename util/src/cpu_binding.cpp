#include "cosim/util/cpu_binding.h"

#include <sched.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "cosim/util/errors.h"

namespace cosim::util {

std::vector<int> allowedCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return {};
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  }
  return cpus;
}

std::vector<int> initialCpus() {
  static const std::vector<int> initial = allowedCpus();
  return initial;
}

void bindThisProcess(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cpus) CPU_SET(c, &set);
  // every thread: the ones already running (ZeroMQ's I/O threads) do not inherit a later mask
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& task : fs::directory_iterator("/proc/self/task", ec)) {
    const pid_t tid = static_cast<pid_t>(std::stol(task.path().filename().string()));
    if (sched_setaffinity(tid, sizeof set, &set) != 0 && errno != ESRCH) {
      throw InputError("cannot bind this process to CPU(s) " + cpuListText(cpus) + ": " +
                       std::strerror(errno));
    }
  }
  if (ec && sched_setaffinity(0, sizeof set, &set) != 0) {
    throw InputError("cannot bind this process to CPU(s) " + cpuListText(cpus) + ": " +
                     std::strerror(errno));
  }
}

std::string cpuListText(const std::vector<int>& cpus) {
  std::string out;
  for (std::size_t i = 0; i < cpus.size();) {
    std::size_t j = i;
    while (j + 1 < cpus.size() && cpus[j + 1] == cpus[j] + 1) ++j;
    if (!out.empty()) out += ",";
    out += std::to_string(cpus[i]);
    if (j > i) out += "-" + std::to_string(cpus[j]);
    i = j + 1;
  }
  return out;
}

}  // namespace cosim::util
