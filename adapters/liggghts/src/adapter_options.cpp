#include "cosim/liggghts/adapter_options.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace cosim::liggghts {

namespace {
const char* kWhere = "scenario file, participants.<particles>.options";

[[noreturn]] void fail(const std::string& key, const std::string& what) {
  throw std::runtime_error(std::string(kWhere) + "." + key + ": " + what);
}
}  // namespace

AdapterOptions AdapterOptions::parse(const std::string& yaml_text) {
  AdapterOptions o;
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(std::string(kWhere) + " is not valid YAML: " + e.what());
  }
  if (!root || root.IsNull())
    throw std::runtime_error(std::string(kWhere) +
                             " is empty; the liggghts adapter needs at least `script: <your "
                             "LIGGGHTS input file>`");
  if (!root.IsMap())
    throw std::runtime_error(std::string(kWhere) + " must be a mapping (key: value)");
  const std::set<std::string> known = {"script", "impact_speed", "dt_check"};
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    if (!known.count(key))
      fail(
          key,
          "unknown option for the liggghts adapter; known options: script, impact_speed, dt_check");
  }
  if (!root["script"])
    fail("script", "missing; give the LIGGGHTS input script, e.g. `script: in.liggghts`");
  try {
    o.script = root["script"].as<std::string>();
  } catch (const YAML::Exception&) {
    fail("script", "expected a file name");
  }
  if (o.script.empty()) fail("script", "is empty; give the LIGGGHTS input script file name");
  if (root["impact_speed"]) {
    try {
      o.impact_speed = root["impact_speed"].as<double>();
    } catch (const YAML::Exception&) {
      fail("impact_speed", "expected a number in m/s, e.g. 2.0");
    }
    if (!(o.impact_speed > 0) || !std::isfinite(o.impact_speed))
      fail("impact_speed", "must be a positive speed in m/s (the largest expected impact speed)");
  }
  if (root["dt_check"]) {
    std::string v;
    try {
      v = root["dt_check"].as<std::string>();
    } catch (const YAML::Exception&) {
      fail("dt_check", "expected one of refuse, warn, off");
    }
    if (v == "refuse")
      o.dt_check = DtCheckPolicy::refuse;
    else if (v == "warn")
      o.dt_check = DtCheckPolicy::warn;
    else if (v == "off")
      o.dt_check = DtCheckPolicy::off;
    else
      fail("dt_check", "'" + v + "' is not one of refuse, warn, off");
  }
  return o;
}

}  // namespace cosim::liggghts
