#include "cosim/util/text_file.h"

#include <deque>
#include <fstream>

namespace cosim::util {

std::optional<std::vector<std::string>> lastLines(const std::filesystem::path& file,
                                                  std::size_t lines) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::deque<std::string> q;
  for (std::string l; std::getline(in, l);) {
    q.push_back(std::move(l));
    if (q.size() > lines) q.pop_front();
  }
  return std::vector<std::string>(q.begin(), q.end());
}

std::string tailOfFile(const std::filesystem::path& file, std::size_t lines) {
  std::string out;
  if (const auto last = lastLines(file, lines)) {
    for (const auto& l : *last) out += l + "\n";
  }
  return out;
}

}  // namespace cosim::util
