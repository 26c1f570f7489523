// Reading YAML text safely: a size limit, yaml-cpp's own nesting limit, then one walk over the
// parsed tree that refuses duplicate keys (yaml-cpp would silently keep the first), lists or
// maps used as keys, nesting deeper than limits::kMaxNesting and more than limits::kMaxNodes
// values once aliases are expanded (nested aliases, "billion laughs"). Every error names where
// the text came from and, for a file, the line.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

namespace cosim::orchestrator {

// `where`: the file name, or "FILE: --set KEY=VALUE" for a value from the command line;
// `lines`: whether line numbers mean something to the user (a file) or not (a --set value).
// Throws ScenarioError.
YAML::Node loadYaml(const std::string& text, const std::string& where, bool lines);

// The text of a scenario file (or an extends: file): a regular file, read up to the size limit
// (never more, whatever the file claims: /proc, /dev). Throws ScenarioError naming the file.
std::string readScenarioFile(const std::filesystem::path& path);

// The walk of loadYaml alone, for a tree parsed elsewhere; `path`: the key the tree is the value
// of ("" for a whole file).
void checkYamlTree(const YAML::Node& root, const std::string& where, bool lines,
                   const std::string& path = "");

}  // namespace cosim::orchestrator
