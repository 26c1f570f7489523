// `cosim piv` and `cosim piv-compare`: the PIV view of a run and its comparison with measured
// profiles (piv_field.h, piv_compare.h), with the defaults a scene gives in its parameters.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <utility>
#include <vector>

namespace cosim::analysis {

// Scene parameters cosim piv takes as defaults (scenario.resolved.yaml of the run).
inline constexpr const char* kPivWallParameter = "piv_front_wall_y";  // [m]
inline constexpr const char* kPivXMinParameter = "piv_x_min";         // [m]
inline constexpr const char* kPivXMaxParameter = "piv_x_max";         // [m]
inline constexpr const char* kPivZMaxParameter = "piv_z_max";         // [m]
inline constexpr const char* kPivDiscardParameter = "piv_discard";    // [s]
inline constexpr const char* kPivFolder = "piv";

struct PivCommandOptions {
  std::filesystem::path run;
  std::optional<double> from, to, depth, wall_y, x_min, x_max, z_min, z_max;
  double cell = 0.004;
  std::vector<double> heights{0.13, 0.15};
  std::size_t blocks = 10;       // time blocks for the profiles' standard errors (piv_field.h)
  std::filesystem::path output;  // default RUN/piv
  bool plots = true;             // piv.png (scripts/plot_piv.py) beside the CSV files
};

// Writes grid.csv, profiles.csv, piv.json (piv_field.h) and piv.png and prints a summary with the
// profiles. Returns the exit code; throws std::runtime_error with what to do on bad input.
int runPivCommand(const PivCommandOptions& options, std::ostream& out);

struct PivCompareCommandOptions {
  std::filesystem::path simulated;  // a run folder (its piv/profiles.csv) or a profile CSV
  std::filesystem::path measured;   // a profile CSV
  std::optional<std::pair<double, double>> core_band;
  std::filesystem::path output;  // default: comparison.csv beside the simulated profiles
  bool plots = true;             // a PNG of the profiles beside it (comparison.png)
  // the two profiles' names in the PNG's legend: another run compared as "measured" (a
  // coarse-graining check) names both runs
  std::string simulated_label = "simulated", measured_label = "measured";
};

// Prints the mean absolute error per profile and region and writes it as CSV
// (height_m,region,points,mae_m_s,noise_mae_m_s; height "all" for every profile together);
// noise_mae_m_s is what the sampling noise alone gives (empty without standard errors),
// and the profiles as a PNG of the same name.
int runPivCompareCommand(const PivCompareCommandOptions& options, std::ostream& out);

}  // namespace cosim::analysis
