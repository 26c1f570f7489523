// What every section parser of a scenario shares: the error that names the file, the line, the
// key, what was expected and what to do; the readers of numbers, texts and sections; the
// declaration of a section's keys (name, default, what it means), checked against the file.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cosim/util/adapter_options.h"
#include "cosim/util/errors.h"

namespace cosim::orchestrator {

// A scenario (its file, an --set or --unset) is wrong: an input error (exit code 1).
class ScenarioError : public InputError {
 public:
  using InputError::InputError;
};

// One key of a section, declared next to the code that reads it: its name, its default
// ("required" if it has none) and what it means, with its unit and the values it allows. The
// same declaration as an adapter's options.
using KeySpec = util::OptionSpec;

// Error helper: "<file>:<line>: <key>: <what>", or "command line --set ...: <key>: <what>" for
// a value that came from the command line. <file> is the file that gave the key: the scenario,
// or the one it extends.
class Context {
 public:
  explicit Context(std::filesystem::path origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& what) const;
  // Where `key` (at `node`) came from, as fail() names it: "FILE:LINE", or "command line --set
  // ..." when a command-line override set it.
  std::string where(const YAML::Node& node, const std::string& key) const;
  [[noreturn]] void failTop(const std::string& key, const std::string& what) const;
  // An error in a command-line override itself (`shown` as given, e.g. "--set a.b=c").
  [[noreturn]] void failCommandLine(const std::string& shown, const std::string& what) const;
  // An override of the command line ("--set KEY=VALUE", "--unset KEY") that changed `path`.
  void addOverride(const std::string& path, const std::string& shown) {
    overrides_.emplace_back(path, shown);
  }
  // The scenario extends `base` (extends:). Key paths of every node of each file (list items as
  // "a[2]"): `base_keys` of base, `own` of the scenario file, `own_values` those of `own` whose
  // node is not a map (it replaces base's whole node). A key is the scenario file's if it gives
  // it or replaces a parent of it, base's if only base gives it, else the scenario file's.
  void setExtends(std::filesystem::path base, std::set<std::string> base_keys,
                  std::set<std::string> own, std::set<std::string> own_values);

  // Refuses keys of `map` not declared in `keys` (a typo), naming the allowed ones.
  void allowOnly(const YAML::Node& map, const std::string& where,
                 const std::vector<std::string>& keys) const;
  void allowOnly(const YAML::Node& map, const std::string& where,
                 const std::vector<KeySpec>& keys) const;
  // The name of a map key; a list or map used as a key is an error.
  std::string keyName(const YAML::Node& key, const std::string& where) const;
  // A section: false if absent or empty; an error if it is anything but a map.
  bool section(const YAML::Node& n, const std::string& key, const std::string& expected) const;

  double number(const YAML::Node& n, const std::string& key) const;
  double positive(const YAML::Node& n, const std::string& key, const std::string& unit) const;
  // A finite number in [lo, hi].
  double inRange(const YAML::Node& n, const std::string& key, double lo, double hi,
                 const std::string& unit) const;
  std::string text(const YAML::Node& n, const std::string& key) const;

  const std::filesystem::path& origin() const { return origin_; }

 private:
  static bool within(const std::string& key, const std::string& path);
  // The file that gave `key` (origin_, or base_ for a key only the extended file gives).
  const std::filesystem::path& fileOf(const std::string& key) const;
  // The override that set `key` or a parent of it; or one below `key` that the message `what`
  // names ('leaf'); nullptr if none.
  const std::pair<std::string, std::string>* blamedOverride(const std::string& key,
                                                            const std::string& what) const;
  // " (the command line changed: ...)" for a message blamed on a file, "" without overrides.
  std::string overridesNote(const std::string& key) const;
  // " (scene FILE)": which scene a command-line override was for.
  std::string sceneNote() const;
  std::filesystem::path origin_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // path, as given
  std::filesystem::path base_;
  std::set<std::string> base_keys_, own_, own_values_;
};

// Names of the keys of a declaration, for allowOnly and messages.
std::vector<std::string> keyNames(const std::vector<KeySpec>& keys);

}  // namespace cosim::orchestrator
