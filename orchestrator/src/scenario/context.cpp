#include "scenario/context.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace cosim::orchestrator {

// `key` is `path` or below it ("a.b" is within "a", "a[2]" within "a", "ab" not within "a").
bool Context::within(const std::string& key, const std::string& path) {
  return key.rfind(path, 0) == 0 &&
         (key.size() == path.size() || key[path.size()] == '.' || key[path.size()] == '[');
}

void Context::setExtends(std::filesystem::path base, std::set<std::string> base_keys,
                         std::set<std::string> own, std::set<std::string> own_values) {
  base_ = std::move(base);
  base_keys_ = std::move(base_keys);
  own_ = std::move(own);
  own_values_ = std::move(own_values);
}

const std::filesystem::path& Context::fileOf(const std::string& key) const {
  if (base_.empty() || own_.count(key)) return origin_;
  for (const auto& v : own_values_)
    if (within(key, v)) return origin_;  // the scenario file replaced a parent of it wholesale
  return base_keys_.count(key) ? base_ : origin_;  // a key neither gives: the scenario's
}

const std::pair<std::string, std::string>* Context::blamedOverride(const std::string& key,
                                                                   const std::string& what) const {
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o)
    if (within(key, o->first)) return &*o;
  // An override below the key whose name the message quotes, e.g. models.drag.k and "parameter
  // 'k' must be a number": the model checks its parameters together, under models.drag.
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (!within(o->first, key)) continue;
    const auto cut = o->first.find_last_of(".[");
    std::string leaf = cut == std::string::npos ? o->first : o->first.substr(cut + 1);
    if (!leaf.empty() && leaf.back() == ']') leaf.pop_back();
    if (!leaf.empty() && what.find("'" + leaf + "'") != std::string::npos) return &*o;
  }
  return nullptr;
}

std::string Context::overridesNote(const std::string& key) const {
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(o->first, key))
      return " (" + o->first + " comes from the command line: " + o->second + ")";
  }
  if (overrides_.empty()) return "";
  std::string list;
  for (const auto& o : overrides_) list += (list.empty() ? "" : ", ") + o.second;
  return " (the command line changed the scene: " + list + ")";
}

std::string Context::sceneNote() const { return " (scene " + origin_.string() + ")"; }

std::string Context::where(const YAML::Node& node, const std::string& key) const {
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(key, o->first)) return "command line " + o->second;
  }
  std::ostringstream out;
  out << fileOf(key).string();
  if (node.IsDefined() && node.Mark().line >= 0) out << ":" << node.Mark().line + 1;
  return out.str();
}

void Context::fail(const YAML::Node& node, const std::string& key, const std::string& what) const {
  // A value that came from the command line has no line in the file: name the override.
  if (const auto* o = blamedOverride(key, what))
    throw ScenarioError("command line " + o->second + ": " + key + ": " + what + sceneNote());
  throw ScenarioError(where(node, key) + ": " + key + ": " + what + overridesNote(key));
}

void Context::failTop(const std::string& key, const std::string& what) const {
  if (const auto* o = blamedOverride(key, what))
    throw ScenarioError("command line " + o->second + ": " + key + ": " + what + sceneNote());
  throw ScenarioError(fileOf(key).string() + ": " + key + ": " + what + overridesNote(key));
}

void Context::failCommandLine(const std::string& shown, const std::string& what) const {
  throw ScenarioError("command line " + shown + ": " + what + sceneNote());
}

std::string Context::keyName(const YAML::Node& key, const std::string& where) const {
  if (!key.IsScalar()) {
    fail(key, where.empty() ? "(top level)" : where,
         "a list or map is used as a key; keys are plain names");
  }
  return key.Scalar();
}

void Context::allowOnly(const YAML::Node& map, const std::string& where,
                        const std::vector<std::string>& keys) const {
  if (!map.IsMap()) return;
  for (const auto& kv : map) {
    const auto k = keyName(kv.first, where);
    if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
      std::string list;
      for (const auto& q : keys) list += (list.empty() ? "" : ", ") + q;
      fail(kv.first, where.empty() ? k : where + "." + k,
           "unknown key (allowed here: " + list + "). Check the spelling.");
    }
  }
}

void Context::allowOnly(const YAML::Node& map, const std::string& where,
                        const std::vector<KeySpec>& keys) const {
  allowOnly(map, where, keyNames(keys));
}

bool Context::section(const YAML::Node& n, const std::string& key,
                      const std::string& expected) const {
  if (!n.IsDefined() || n.IsNull()) return false;
  if (!n.IsMap()) {
    fail(n, key,
         "expected a section (a map of keys) " + expected +
             (n.IsScalar() ? ", got the value '" + n.Scalar() + "'" : ", got a list"));
  }
  return true;
}

double Context::number(const YAML::Node& n, const std::string& key) const {
  if (!n.IsDefined() || n.IsNull()) fail(n, key, "missing; expected a number");
  if (!n.IsScalar()) fail(n, key, "expected a number, got a list or map");
  const std::string& s = n.Scalar();
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') fail(n, key, "expected a number, got '" + s + "'");
  if (!std::isfinite(v)) fail(n, key, "expected a finite number, got '" + s + "'");
  return v;
}

double Context::positive(const YAML::Node& n, const std::string& key,
                         const std::string& unit) const {
  double v = number(n, key);
  if (!(v > 0)) fail(n, key, "must be > 0 " + unit + ", got " + n.Scalar());
  return v;
}

double Context::inRange(const YAML::Node& n, const std::string& key, double lo, double hi,
                        const std::string& unit) const {
  double v = number(n, key);
  if (v < lo || v > hi) {
    std::ostringstream os;
    os << "expected " << unit << " in [" << lo << ", " << hi << "], got " << n.Scalar();
    fail(n, key, os.str());
  }
  return v;
}

std::string Context::text(const YAML::Node& n, const std::string& key) const {
  if (!n.IsDefined() || n.IsNull()) fail(n, key, "missing; expected a text value");
  if (!n.IsScalar()) fail(n, key, "expected a text value, got a list or map");
  return n.Scalar();
}

std::vector<std::string> keyNames(const std::vector<KeySpec>& keys) {
  std::vector<std::string> out;
  out.reserve(keys.size());
  for (const auto& k : keys) out.push_back(k.name);
  return out;
}

}  // namespace cosim::orchestrator
