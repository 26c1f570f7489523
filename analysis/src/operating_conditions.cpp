// The operating conditions at the top of a report (operating_conditions.h).
#include "cosim/analysis/operating_conditions.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cosim/analysis/minimum_fluidization.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {
constexpr const char* kResolvedScene = "scenario.resolved.yaml";

double parameter(const ConditionInputs& in, const std::string& name) {
  for (const auto& [n, v] : in.parameters) {
    if (n == name) return v;
  }
  return std::nan("");
}

// A number under node[key] (nullopt when absent or not a number).
std::optional<double> number(const YAML::Node& node, const char* key) {
  if (!node || !node.IsMap() || !node[key] || !node[key].IsScalar()) return std::nullopt;
  try {
    return node[key].as<double>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

// What the report needs from the scene as it was run: the grains' density, gravity and the gas.
struct Scene {
  std::optional<double> cg, particle_density, gravity;
  bool openfoam_gas = false;  // the fluid is cosimFoam: its gas options (or defaults) apply
  double viscosity = 1.8e-5, molar_mass = 0.0280134, temperature = 300.0;  // cosimFoam defaults
};

std::optional<Scene> readScene(const std::filesystem::path& run) {
  const auto path = run / kResolvedScene;
  if (!std::filesystem::exists(path)) return std::nullopt;
  YAML::Node root;
  try {
    root = YAML::LoadFile(path.string());
  } catch (const YAML::Exception& e) {
    throw InputError(path.string() + ": cannot be read as YAML (" + e.what() +
                     "); it is written by `cosim run`: restore it or move it away to "
                     "report the run without the scene's constants");
  }
  Scene s;
  const auto constants = root["constants"];
  s.cg = number(constants, "cg");
  s.particle_density = number(constants, "particle_density");
  if (constants && constants.IsMap() && constants["gravity"] && constants["gravity"].IsSequence()) {
    double g2 = 0;
    for (const auto& c : constants["gravity"]) g2 += c.as<double>(0.0) * c.as<double>(0.0);
    if (g2 > 0) s.gravity = std::sqrt(g2);
  }
  const auto participants = root["participants"];
  if (participants && participants.IsMap()) {
    for (const auto& p : participants) {
      const auto& node = p.second;
      if (!node.IsMap() || !node["adapter"] || node["adapter"].as<std::string>("") != "openfoam")
        continue;
      s.openfoam_gas = true;
      const auto options = node["options"];
      s.viscosity = number(options, "viscosity").value_or(s.viscosity);
      s.molar_mass = number(options, "molar_mass").value_or(s.molar_mass);
      s.temperature = number(options, "temperature").value_or(s.temperature);
    }
  }
  return s;
}
}  // namespace

OperatingConditions readOperatingConditions(const ConditionInputs& in, const ParticleFile& file) {
  OperatingConditions c;
  const auto scene = readScene(in.run);
  const auto& snaps = file.snapshots();

  c.flow_lpm = parameter(in, kFlowParameter);
  for (const char* name : kSuperficialVelocityParameters) {
    if (std::isnan(c.superficial_velocity)) {
      c.superficial_velocity = parameter(in, name);
      c.superficial_velocity_parameter = name;
    }
  }
  c.nozzle_velocity = parameter(in, kNozzleVelocityParameter);
  c.precursor_fraction = parameter(in, kPrecursorFractionParameter);
  if (!snaps.empty()) {
    c.parcels = snaps.back().count;
    c.coating_time = snaps.back().time - std::max(snaps.front().time, in.coating_start);
  }

  // Coarse graining: what the run used (summary.json), else the scene's constant.
  if (in.cg) {
    c.grain.cg = *in.cg;
    c.cg_source = "summary.json";
  } else if (scene && scene->cg) {
    c.grain.cg = *scene->cg;
    c.cg_source = std::string(kResolvedScene) + " constants.cg";
  } else {
    c.grain.cg = 1.0;
    c.cg_source = "not recorded (no summary.json): 1 assumed, parcels taken as real grains";
  }

  // Parcel diameter: the recorded radii at the last snapshot, else the scene parameter dp.
  if (!snaps.empty() && file.hasField(cosim::field::radius) && snaps.back().count > 0) {
    const auto r = file.read(snaps.size() - 1, cosim::field::radius);
    double sum = 0;
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    for (double x : r) sum += x;
    c.parcel_diameter = 2.0 * sum / static_cast<double>(r.size());
    c.polydisperse = *hi > 1.01 * *lo;
    c.parcel_diameter_source = c.polydisperse
                                   ? "particles.h5 radius (mean: the parcels differ in size)"
                                   : "particles.h5 radius";
  } else if (const double dp = parameter(in, kParcelDiameterParameter); dp > 0) {
    c.parcel_diameter = dp;
    c.parcel_diameter_source = std::string("scene parameter ") + kParcelDiameterParameter;
  }
  c.grain.grain_diameter = c.parcel_diameter / c.grain.cg;

  // Coating density: report option, else the scene, else the documented default.
  if (std::isfinite(in.coating_density)) {
    c.grain.coating_density = in.coating_density;
    c.coating_density_source = "cosim report --coating-density";
  } else if (const double rho = parameter(in, kCoatingDensityParameter); rho > 0) {
    c.grain.coating_density = rho;
    c.coating_density_source = std::string("scene parameter ") + kCoatingDensityParameter;
  } else {
    c.grain.coating_density = kDefaultCoatingDensity;
    c.coating_density_source =
        fmt::format("default (the scene gives no {}; set it there or with --coating-density)",
                    kCoatingDensityParameter);
  }

  // u_mf: report option, else the scene, else Wen-Yu for the real grains in the fluid's gas.
  if (std::isfinite(in.u_mf)) {
    c.u_mf = in.u_mf;
    c.u_mf_source = "cosim report --u-mf";
  } else if (const double u = parameter(in, kMinimumFluidizationParameter); u > 0) {
    c.u_mf = u;
    c.u_mf_source = std::string("scene parameter ") + kMinimumFluidizationParameter;
  } else if (scene && scene->openfoam_gas && scene->particle_density &&
             c.grain.grain_diameter > 0) {
    double p = parameter(in, kOutletPressureParameter);
    if (!(p > 0)) p = 1e5;
    const double rhoGas = idealGasDensity(p, scene->molar_mass, scene->temperature);
    c.u_mf = wenYuMinimumFluidization(c.grain.grain_diameter, *scene->particle_density, rhoGas,
                                      scene->viscosity, scene->gravity.value_or(9.81));
    if (std::isfinite(c.u_mf)) {
      c.u_mf_source = fmt::format(
          "Wen-Yu for the real grains ({:.3g} µm, {:.4g} kg/m3) in the gas ({:.4g} kg/m3, {:.3g} "
          "Pa s); "
          "the scene gives no {}",
          1e6 * c.grain.grain_diameter, *scene->particle_density, rhoGas, scene->viscosity,
          kMinimumFluidizationParameter);
    }
  }
  return c;
}

}  // namespace cosim::analysis
