#include "case_files.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

int copyCaseFiles(const fs::path& from, const fs::path& to, const Variables& vars) {
  int templated = 0;
  fs::create_directories(to);
  for (const auto& entry : fs::recursive_directory_iterator(from)) {
    const fs::path rel = fs::relative(entry.path(), from);
    const fs::path dest = to / rel;
    if (entry.is_directory()) {
      fs::create_directories(dest);
      continue;
    }
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream ss;
    if (!in || (!(ss << in.rdbuf()) && fs::file_size(entry.path()) > 0)) {
      const int err = errno;
      throw Error(kindOfErrno(err),
                  "cannot read the case file " + entry.path().string() + ": " + std::strerror(err));
    }
    std::string text = ss.str();
    const bool binary = text.find('\0') != std::string::npos;
    if (!binary && text.find("${") != std::string::npos) {
      std::string out;
      std::istringstream lines(text);
      int n = 0;
      for (std::string line; std::getline(lines, line);) {
        ++n;
        try {
          out += substitute(line, vars);
        } catch (const ExpressionError& e) {
          throw ExpressionError(entry.path().string() + ":" + std::to_string(n) + ": " + e.what());
        }
        if (!lines.eof()) out += '\n';
      }
      if (!text.empty() && text.back() == '\n' && (out.empty() || out.back() != '\n')) out += '\n';
      text = out;
      ++templated;
    }
    try {
      analysis::overwriteFile(dest, text);
    } catch (const std::exception& e) {
      std::error_code ec;
      fs::remove(dest, ec);  // no truncated copy for the solver to trip over
      throw Error(kindOf(e, ErrorKind::resource),
                  std::string(e.what()) + " (copying the case file " + entry.path().string() + ")");
    }
    fs::permissions(dest, fs::status(entry.path()).permissions());
  }
  return templated;
}

}  // namespace cosim::orchestrator
