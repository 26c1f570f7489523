#include "scenario/yaml_input.h"

#include <yaml-cpp/depthguard.h>

#include <fstream>
#include <map>

#include "scenario/context.h"
#include "scenario/limits.h"

namespace cosim::orchestrator {

namespace {

std::string nestingTooDeep() {
  return "nested more than " + std::to_string(limits::kMaxNesting) +
         " levels deep (maps and lists inside each other); a scenario needs a few";
}

class Walk {
 public:
  Walk(const std::string& where, bool lines) : where_(where), lines_(lines) {}

  void node(const YAML::Node& n, const std::string& path, int depth) {
    if (++count_ > limits::kMaxNodes) {
      fail(n, path,
           "more than " + std::to_string(limits::kMaxNodes) +
               " values once its aliases (*name) are expanded; nested aliases? Write the values "
               "out, or use fewer levels of aliases");
    }
    if (depth > limits::kMaxNesting) {
      fail(n, path, nestingTooDeep());
    }
    if (n.IsMap()) {
      std::map<std::string, int> seen;  // key -> line (1-based)
      for (const auto& kv : n) {
        if (!kv.first.IsScalar()) {
          fail(kv.first, path, "a list or map is used as a key; keys are plain names");
        }
        const std::string k = kv.first.Scalar();
        const std::string child = path.empty() ? k : path + "." + k;
        const int line = kv.first.Mark().line + 1;
        auto [it, fresh] = seen.emplace(k, line);
        if (!fresh) {
          fail(kv.first, child,
               "duplicate key" +
                   (lines_ && it->second > 0 ? " (first at line " + std::to_string(it->second) + ")"
                                             : std::string()) +
                   "; YAML keeps only one of them: remove or rename the other");
        }
        node(kv.second, child, depth + 1);
      }
    } else if (n.IsSequence()) {
      for (std::size_t i = 0; i < n.size(); ++i) {
        node(n[i], path + "[" + std::to_string(i) + "]", depth + 1);
      }
    }
  }

 private:
  [[noreturn]] void fail(const YAML::Node& n, const std::string& path,
                         const std::string& what) const {
    std::string msg = where_;
    if (lines_ && n.IsDefined() && n.Mark().line >= 0)
      msg += ":" + std::to_string(n.Mark().line + 1);
    msg += ": " + (path.empty() ? std::string("(top level)") : path) + ": " + what;
    throw ScenarioError(msg);
  }

  const std::string& where_;
  bool lines_;
  std::size_t count_ = 0;
};

}  // namespace

std::string readScenarioFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ScenarioError(
        path.string() +
        ": cannot open the scenario file (does it exist? a scenario folder needs a scenario.yaml)");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ScenarioError(path.string() + ": not a regular file; give a scenario.yaml");
  }
  std::string text(limits::kMaxFileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > limits::kMaxFileBytes) {
    throw ScenarioError(path.string() + ": more than the " + std::to_string(limits::kMaxFileBytes) +
                        " bytes a scenario may have; is this the right file?");
  }
  return text;
}

YAML::Node loadYaml(const std::string& text, const std::string& where, bool lines) {
  if (text.size() > limits::kMaxFileBytes) {
    throw ScenarioError(where + ": " + std::to_string(text.size()) + " bytes, more than the " +
                        std::to_string(limits::kMaxFileBytes) +
                        " a scenario may have; is this the right file?");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // brackets nested deeper than the parser follows: what the tree check says of fewer levels
    throw ScenarioError(where + (lines ? ":" + std::to_string(e.mark.line + 1) : std::string()) +
                        ": " + nestingTooDeep());
  } catch (const YAML::Exception& e) {
    throw ScenarioError(where + (lines ? ":" + std::to_string(e.mark.line + 1) : std::string()) +
                        ": not valid YAML: " + e.msg);
  }
  checkYamlTree(root, where, lines);
  return root;
}

void checkYamlTree(const YAML::Node& root, const std::string& where, bool lines,
                   const std::string& path) {
  Walk(where, lines).node(root, path, 0);
}

}  // namespace cosim::orchestrator
