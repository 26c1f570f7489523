// The operating conditions a report opens with: gas flow, superficial velocity and u / u_mf,
// nozzle gas, precursor fraction, parcels, coarse-graining, coating time, and the grain scale
// (real grain diameter, coating density) that turns a parcel's coating into a real grain's.
// Read from the run folder: summary.json (scenario parameters, cg), scenario.resolved.yaml
// (constants, the fluid's gas) and particles.h5 (parcel radius and count). Which scene
// parameter gives which condition, and the defaults: docs/analysis.md section 8.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/grain_scale.h"
#include "cosim/analysis/particle_file.h"

namespace cosim::analysis {

// Coating density used for the layer thickness when neither the scene (parameter
// `coating_density`) nor `cosim report --coating-density` gives one [kg/m3]: an organosilicon
// plasma polymer lies between its siloxane (about 970 kg/m3) and silica (2200 kg/m3).
inline constexpr double kDefaultCoatingDensity = 1500.0;

// Scene parameters read as operating conditions (summary.json extra.parameters).
inline constexpr const char* kFlowParameter = "flow_lpm";  // [L/min]
inline constexpr const char* kSuperficialVelocityParameters[] = {"u_fluidization", "u0"};  // [m/s]
inline constexpr const char* kMinimumFluidizationParameter = "u_mf";                       // [m/s]
inline constexpr const char* kNozzleVelocityParameter = "u_nozzle";                        // [m/s]
inline constexpr const char* kPrecursorFractionParameter = "Y_nozzle";                     // [-]
inline constexpr const char* kCoatingDensityParameter = "coating_density";  // [kg/m3]
inline constexpr const char* kParcelDiameterParameter = "dp";     // [m] without a radius field
inline constexpr const char* kOutletPressureParameter = "p_out";  // [Pa] gas density for Wen-Yu

struct ConditionInputs {
  std::filesystem::path run;                               // the run folder
  std::vector<std::pair<std::string, double>> parameters;  // summary.json extra.parameters
  std::optional<double> cg;                                // summary.json extra.cg
  double coating_start = 0;                                // [s] report option
  double coating_density = std::numeric_limits<double>::quiet_NaN();  // override [kg/m3]
  double u_mf = std::numeric_limits<double>::quiet_NaN();             // override [m/s]
};

struct OperatingConditions {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double flow_lpm = nan;                       // [L/min]
  double superficial_velocity = nan;           // [m/s]
  std::string superficial_velocity_parameter;  // the scene parameter it came from
  double u_mf = nan;                           // [m/s]
  std::string u_mf_source;                     // where u_mf comes from, in words (empty: none)
  double nozzle_velocity = nan;                // [m/s]
  double precursor_fraction = nan;             // [-] mass fraction in the nozzle gas
  std::size_t parcels = 0;                     // at the last snapshot
  double coating_time = nan;     // [s] last snapshot - max(first snapshot, coating start)
  double parcel_diameter = nan;  // [m]
  std::string parcel_diameter_source;
  bool polydisperse = false;  // parcel radii differ by more than 1 %: mean diameter used
  GrainScale grain;           // cg, real grain diameter, coating density
  std::string cg_source, coating_density_source;

  double uOverUmf() const { return superficial_velocity / u_mf; }
};

// Throws std::runtime_error naming scenario.resolved.yaml when it exists but cannot be read.
OperatingConditions readOperatingConditions(const ConditionInputs& in, const ParticleFile& file);

}  // namespace cosim::analysis
