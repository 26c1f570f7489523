// Runs a fuzz target's LLVMFuzzerTestOneInput over given inputs without libFuzzer: the replay
// of the fuzz seeds, dictionaries and saved corpus in the normal (uninstrumented) build, as a
// ctest (fuzz/CMakeLists.txt). Arguments are files or folders (searched recursively); in a file
// ending in .dict every quoted token is an input of its own. An input that crashes or throws
// ends the program, naming it; otherwise it prints how many inputs it ran.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The tokens of a libFuzzer dictionary: the text between the quotes of each line.
std::vector<std::string> dictionaryTokens(const std::string& text) {
  std::vector<std::string> tokens;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const auto open = line.find('"');
    const auto close = line.rfind('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
    tokens.push_back(line.substr(open + 1, close - open - 1));
  }
  return tokens;
}

std::size_t run(const std::string& input, const std::string& name) {
  try {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: escaped the fuzz target: %s\n", name.c_str(), e.what());
    std::exit(1);
  }
  return 1;
}

std::size_t replay(const fs::path& p) {
  if (fs::is_directory(p)) {
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(p))
      if (e.is_regular_file()) n += replay(e.path());
    return n;
  }
  const std::string text = readFile(p);
  if (p.extension() != ".dict") return run(text, p.string());
  std::size_t n = 0;
  for (const auto& token : dictionaryTokens(text)) n += run(token, p.string() + ": " + token);
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE_OR_FOLDER...\n", argv[0]);
    return 2;
  }
  std::size_t n = 0;
  for (int i = 1; i < argc; ++i) {
    if (!fs::exists(argv[i])) {
      std::fprintf(stderr, "%s: no such file or folder\n", argv[i]);
      return 2;
    }
    n += replay(argv[i]);
  }
  std::printf("%zu inputs replayed without a crash\n", n);
  return 0;
}
