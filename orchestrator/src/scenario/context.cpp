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

std::string Context::where(const YAML::Node& node, const std::string& key) const {
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(key, o->first)) return origin_.string() + ": " + o->second;
  }
  std::ostringstream out;
  out << origin_.string();
  if (node.IsDefined() && node.Mark().line >= 0) out << ":" << node.Mark().line + 1;
  return out.str();
}

void Context::fail(const YAML::Node& node, const std::string& key, const std::string& what) const {
  std::ostringstream os;
  os << origin_.string();
  // A value that came from the command line has no line in the file: name the override.
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(key, o->first)) {
      os << ": " << o->second << ": " << key << ": " << what;
      throw ScenarioError(os.str());
    }
  }
  if (node.IsDefined() && node.Mark().line >= 0) os << ":" << node.Mark().line + 1;
  os << ": " << key << ": " << what;
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(o->first, key)) {
      os << " (" << o->first << " comes from the command line: " << o->second << ")";
      break;
    }
  }
  throw ScenarioError(os.str());
}

void Context::failTop(const std::string& key, const std::string& what) const {
  for (auto o = overrides_.rbegin(); o != overrides_.rend(); ++o) {
    if (within(key, o->first)) {
      throw ScenarioError(origin_.string() + ": " + o->second + ": " + key + ": " + what);
    }
  }
  throw ScenarioError(origin_.string() + ": " + key + ": " + what);
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
  const std::string s = n.Scalar();
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
