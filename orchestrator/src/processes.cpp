#include "processes.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include "cosim/util/text_file.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

std::string tailOfFile(const fs::path& file, int lines) {
  const auto last = util::lastLines(file, static_cast<std::size_t>(std::max(lines, 0)));
  if (!last) return "(no log at " + file.string() + ")";
  std::string out;
  for (const auto& l : *last) out += "    | " + l + "\n";
  return out.empty() ? "    | (log is empty)\n" : out;
}

std::optional<fs::path> findExecutable(const std::string& name) {
  if (name.find('/') != std::string::npos) {
    if (access(name.c_str(), X_OK) == 0) return fs::absolute(name);
    return std::nullopt;
  }
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path beside = self.parent_path() / name;
    if (access(beside.c_str(), X_OK) == 0) return beside;
  }
  if (const char* path = std::getenv("PATH")) {
    std::string p = path;
    std::size_t b = 0;
    while (b <= p.size()) {
      std::size_t e = p.find(':', b);
      if (e == std::string::npos) e = p.size();
      fs::path cand = fs::path(p.substr(b, e - b)) / name;
      if (access(cand.c_str(), X_OK) == 0) return cand;
      b = e + 1;
    }
  }
  return std::nullopt;
}

}  // namespace cosim::orchestrator
