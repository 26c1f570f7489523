#include "cosim/analysis/files.h"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace cosim::analysis {

std::string formatShortest(double v) { return fmt::format("{}", v); }

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f)
      throw std::runtime_error("cannot write " + tmp.string() +
                               ": check the folder exists and is writable");
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("writing " + tmp.string() + " failed (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec)
    throw std::runtime_error("cannot rename " + tmp.string() + " to " + path.string() + ": " +
                             ec.message());
}

void writeJsonFile(const std::filesystem::path& path, const Json& json, int indent) {
  writeFileAtomically(path, json.dump(indent, ' ', false, Json::error_handler_t::replace) + "\n");
}

Json readJsonFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  try {
    return Json::parse(text.str());
  } catch (const Json::exception& e) {
    throw std::runtime_error(path.string() + " is not valid JSON (" + e.what() + ")");
  }
}

}  // namespace cosim::analysis
