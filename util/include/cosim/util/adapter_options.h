// An adapter's options: the `participants.<name>.options` map of the scenario, which the
// orchestrator hands over as it is (Welcome.config_yaml). Each adapter declares its options
// (name, default, meaning) in one list, next to the code that reads them; the reader refuses a
// key the list does not hold, and every error names the scenario key, what was expected and
// what was given. The same list prints the adapter's option table (`--options-reference`), so
// the adapter's page of the manual is made from it. C++17: the OpenFOAM adapter uses it too.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <string>
#include <vector>

namespace cosim::util {

struct OptionSpec {
  std::string name;
  std::string default_value;  // "required" for an option without a default
  std::string doc;            // what it is, its unit and the values it allows
};

// The options as a Markdown table: | option | default | meaning |, each name in backquotes after
// `prefix` ("coupling."); '|' escaped, '<' before a letter written &lt; (not an HTML tag).
std::string optionsTable(const std::vector<OptionSpec>& specs,
                         const std::string& heading = "option", const std::string& prefix = "");

class AdapterOptions {
 public:
  // `participant`: the scenario's name of it ("fluid", "particles"); `adapter`: the program
  // ("cosimFoam"); `page`: where its options are explained ("docs/openfoam.md"). Throws
  // InputError for text that is not a YAML map or a key that `specs` does not declare.
  AdapterOptions(const std::string& yaml, const std::string& participant, std::string adapter,
                 const std::vector<OptionSpec>& specs, std::string page);

  bool has(const std::string& key) const { return static_cast<bool>(root_[key]); }
  bool empty() const { return root_.size() == 0; }
  bool isList(const std::string& key) const { return has(key) && root_[key].IsSequence(); }

  // A finite number in [lo, hi], or `fallback` when the key is absent.
  double number(const std::string& key, double fallback, double lo = -1.7976931348623157e308,
                double hi = 1.7976931348623157e308) const;
  // A number > 0 (and finite), or `fallback`.
  double positive(const std::string& key, double fallback) const;
  // A whole number in [lo, hi], or `fallback`.
  int whole(const std::string& key, int fallback, int lo, int hi) const;
  bool flag(const std::string& key, bool fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
  // A text that must be given and not be empty
  std::string requiredText(const std::string& key, const std::string& example) const;
  // One of `allowed`, or `fallback`.
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& allowed) const;
  std::array<double, 3> vec3(const std::string& key, const std::array<double, 3>& fallback) const;
  // One name or a list of names
  std::vector<std::string> names(const std::string& key,
                                 const std::vector<std::string>& fallback) const;

  // A nested option (a list of maps, a map): its node, and its values read by their path
  // ("lattice.spacing", "particles[2].radius"), with the same errors.
  YAML::Node node(const std::string& key) const { return root_[key]; }
  double numberAt(const YAML::Node& n, const std::string& path) const;
  std::array<double, 3> vec3At(const YAML::Node& n, const std::string& path) const;

  // "scenario participants.fluid.options.KEY"
  std::string keyName(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  std::string got(const YAML::Node& n) const;
  YAML::Node root_;
  std::string where_;  // "scenario participants.fluid.options"
  std::string adapter_;
  std::string page_;
};

}  // namespace cosim::util
