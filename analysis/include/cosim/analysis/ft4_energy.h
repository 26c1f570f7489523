// The FT4 rheometer's flow energy (the paper's Eq. 11) from the blade's force and torque
// against its height: W = integral of (M / (R tan alpha) + F) dH over the blade's descent,
// R the blade radius, alpha the helix angle of the tip's path (so that dH = R tan(alpha) dtheta
// and M dtheta + F dH is the work the drive does). Used by `cosim ft4 energy` and
// `cosim ft4 calibrate`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cosim::analysis {

// One row of RUN/particles/ft4_blade.csv (written by the scene's LIGGGHTS script): means over
// the output interval ending at time_s. The file's fifth column `averaged` is 1 for a row that
// holds a mean and 0 for the interval in which a resumed run started (LIGGGHTS' fix ave/time
// averages whole intervals only, so that one has none); files of runs made before that column
// have four.
struct BladeRow {
  double time_s = 0;
  double height_m = 0;   // blade reference point above the vessel base
  double force_N = 0;    // vertical force of the grains on the blade, positive up (resisting)
  double torque_Nm = 0;  // torque about the axis, positive resisting the rotation
};

// Reads ft4_blade.csv. A resumed run appends to the file from its checkpoint, so a header line
// may repeat and times may go back: a row replaces every earlier row of the same or a later
// time (the newest rows win). Rows with `averaged` 0 are left out (their times go to
// cut_windows when given); the profile then joins the rows on either side. Throws
// std::runtime_error naming the file, line and what was expected for anything else (missing
// columns, a number that is not one).
std::vector<BladeRow> readBladeRows(const std::filesystem::path& csv,
                                    std::vector<double>* cut_windows = nullptr);

// A point of the energy profile: the work done from the first row down to this row's height.
struct EnergyPoint {
  double height_m = 0;
  double force_N = 0;
  double torque_Nm = 0;
  double gradient_J_per_m = 0;  // M / (R tan alpha) + F
  double energy_J = 0;          // cumulative, trapezoid rule over the heights
  double torque_energy_J = 0;   // the part of energy_J from the torque term M / (R tan alpha)
};

struct EnergyProfile {
  double blade_radius_m = 0;
  double helix_deg = 0;
  std::vector<EnergyPoint> points;    // the rows in time order; only descending steps add work
  std::vector<double> cut_windows_s;  // times of rows left out: intervals a resume cut
  double total_J() const { return points.empty() ? 0.0 : points.back().energy_J; }
  // the torque term's share of total_J (the rest is the vertical force's): which of the two
  // a change of the powder or the model moves
  double torque_J() const { return points.empty() ? 0.0 : points.back().torque_energy_J; }
  // Work done while the blade's height went from h_high down to h_low (the cumulative energy
  // interpolated linearly in height). Throws std::invalid_argument when the profile does not
  // cover [h_low, h_high] (names both ranges).
  double between(double h_low, double h_high) const;
  double lowest_m() const;
  double highest_m() const;
};

// Integrates Eq. 11 with the trapezoid rule over consecutive rows. Rows whose height does not
// fall (the blade waits, or a row repeats its height) add nothing. Throws std::invalid_argument
// for R <= 0 or alpha outside (0, 90) degrees, and when the height rises between two rows (this
// is the downward test).
EnergyProfile flowEnergy(const std::vector<BladeRow>& rows, double blade_radius_m,
                         double helix_deg);

// The blade parameters of a run folder: `blade_radius` and `helix_deg` from its
// scenario.resolved.yaml; plus the parameter named `parameter` (e.g. mu_fric) when not empty.
struct Ft4RunParameters {
  double blade_radius_m = 0;
  double helix_deg = 0;
  double parameter = 0;
};
Ft4RunParameters readFt4RunParameters(const std::filesystem::path& run,
                                      const std::string& parameter = "");

// The profile of a run folder: RUN/particles/ft4_blade.csv integrated with its parameters.
EnergyProfile runFlowEnergy(const std::filesystem::path& run);

// CSV text of a profile: height_m, force_N, torque_Nm, gradient_J_per_m, energy_J.
std::string energyProfileCsv(const EnergyProfile& profile);

}  // namespace cosim::analysis
