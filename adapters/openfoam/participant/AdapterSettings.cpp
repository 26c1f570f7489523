#include "AdapterSettings.h"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <set>
#include <stdexcept>

#include "cosim/util/format.h"

namespace cosim::foam {
namespace {

const char* const kWhere = "scenario participants.<fluid>.options";

std::runtime_error bad(const std::string& key, const std::string& expected) {
  return std::runtime_error(std::string(kWhere) + "." + key + ": expected " + expected);
}

double number(const YAML::Node& n, const std::string& key, double lo, double hi) {
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw bad(key, "a number, got '" + YAML::Dump(n) + "'");
  }
  if (!(v >= lo && v <= hi)) {
    throw bad(key, "a value in [" + cosim::util::exact(lo) + ", " + cosim::util::exact(hi) +
                       "], got " + cosim::util::exact(v));
  }
  return v;
}

std::vector<std::string> names(const YAML::Node& n, const std::string& key) {
  std::vector<std::string> out;
  if (n.IsScalar()) {
    out.push_back(n.as<std::string>());
  } else if (n.IsSequence()) {
    for (const auto& e : n) {
      if (!e.IsScalar()) throw bad(key, "a list of patch names");
      out.push_back(e.as<std::string>());
    }
  } else {
    throw bad(key, "a patch name or a list of patch names");
  }
  return out;
}

}  // namespace

AdapterSettings parseAdapterSettings(const std::string& yaml, bool species) {
  AdapterSettings s;
  s.gas.species = species;
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(std::string(kWhere) + ": not valid YAML: " + e.what());
  }
  if (!root || root.IsNull()) return s;
  if (!root.IsMap()) throw std::runtime_error(std::string(kWhere) + ": expected a mapping");

  static const std::set<std::string> known{
      "temperature", "molar_mass",        "viscosity",       "schmidt",
      "min_voidage", "voidage_divisions", "inlet_patches",   "outlet_patches",
      "mesh",        "hydrostatic_start", "solver_log_every"};
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    if (!known.count(key)) {
      throw std::runtime_error(
          std::string(kWhere) + ": unknown key '" + key +
          "' (cosimFoam knows temperature, molar_mass, viscosity, schmidt, min_voidage, "
          "voidage_divisions, inlet_patches, outlet_patches, mesh, hydrostatic_start, "
          "solver_log_every; see docs/openfoam.md)");
    }
  }
  if (root["temperature"]) s.gas.temperature = number(root["temperature"], "temperature", 1, 1e4);
  if (root["molar_mass"]) s.gas.molar_mass = number(root["molar_mass"], "molar_mass", 1e-4, 1);
  if (root["viscosity"]) s.gas.viscosity = number(root["viscosity"], "viscosity", 1e-8, 1e3);
  if (root["schmidt"]) s.gas.schmidt = number(root["schmidt"], "schmidt", 1e-6, 1e6);
  if (root["min_voidage"]) s.gas.min_voidage = number(root["min_voidage"], "min_voidage", 0.01, 1);
  if (root["voidage_divisions"]) {
    const double d = number(root["voidage_divisions"], "voidage_divisions", 1, 9);
    if (d != static_cast<int>(d)) throw bad("voidage_divisions", "an integer from 1 to 9");
    s.gas.voidage_divisions = static_cast<int>(d);
  }
  if (root["solver_log_every"]) {
    const double d = number(root["solver_log_every"], "solver_log_every", 1, 1e9);
    if (d != static_cast<int>(d))
      throw bad("solver_log_every", "a whole number of gas steps >= 1 (1: every step)");
    s.gas.solver_log_every = static_cast<int>(d);
  }
  if (root["inlet_patches"]) s.gas.inlet_patches = names(root["inlet_patches"], "inlet_patches");
  if (root["outlet_patches"]) {
    s.gas.outlet_patches = names(root["outlet_patches"], "outlet_patches");
  }
  if (root["hydrostatic_start"]) {
    const auto& n = root["hydrostatic_start"];
    bool v = false;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v))
      throw bad("hydrostatic_start", "true or false");
    s.gas.hydrostatic_start = v;
  }
  if (root["mesh"]) {
    s.mesh = root["mesh"].as<std::string>();
    if (s.mesh != "auto" && s.mesh != "blockMesh" && s.mesh != "existing") {
      throw bad("mesh", "auto, blockMesh or existing, got '" + s.mesh + "'");
    }
  }
  return s;
}

}  // namespace cosim::foam
