// Calibrating a DEM parameter (the friction coefficient) against a measured FT4 flow energy:
// the study's runs give the simulated energy W at each value of the parameter, a straight line
// W = a + b mu is fitted to them by least squares, and the measured energy is read back
// through it, mu = (W_measured - a) / b. The uncertainty combines the scatter of the runs
// about the line (the line's standard error at mu, from the residual spread) and that of the
// measurement (the standard error of its replicates):
//   sigma_mu^2 = (s^2 (1/n + (mu - mean mu)^2 / Sxx) + sigma_W^2) / b^2.
// docs/calibration-validation.md section 1 describes the method and the commands.
#pragma once

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/ft4_energy.h"

namespace cosim::analysis {

// A measured flow energy: one value per replicate [J], over the heights [low, high] when it
// came from a profile (none: the whole simulated descent).
struct MeasuredEnergy {
  std::vector<double> replicates_J;
  std::optional<double> height_low_m, height_high_m;
  double mean_J() const;
  double standard_error_J() const;  // std / sqrt(n); 0 for a single value
};

// Reads a measured CSV (header line, comma separated). Two forms:
//  - totals: one column energy_J or energy_mJ, one row per replicate;
//  - a profile: a column height_m or height_mm and one or more columns whose name starts with
//    energy_J or energy_mJ (one per replicate), the cumulative energy from the start of the
//    test; each replicate's energy is its value at the lowest height minus that at the
//    highest.
// Throws std::runtime_error naming the file, line or column and what was expected.
MeasuredEnergy readMeasuredEnergy(const std::filesystem::path& csv);

struct CalibrationPoint {
  std::filesystem::path run;
  double parameter = 0;
  double energy_J = 0;
};

struct Calibration {
  std::vector<CalibrationPoint> points;
  double intercept_J = 0, slope_J = 0;  // W = a + b mu
  double residual_sd_J = 0;             // s, with n - 2 degrees of freedom
  double measured_J = 0, measured_se_J = 0;
  double parameter = 0;          // the value that matches
  double sigma = 0;              // its standard uncertainty
  double sigma_study = 0;        // the part from the runs' spread about the line
  double sigma_measurement = 0;  // the part from the measurement's replicates
  bool extrapolated = false;     // outside the studied values
  // The same measurement read between the two studied values whose mean energies bracket it
  // (linear between them; none when no pair or more than one pair does): where the energy bends
  // over the studied range the line misleads, and this answer tells it apart from the line's.
  std::optional<double> bracketed;
  double bracket_low = 0, bracket_high = 0;  // the two parameter values
  // the line's answer and the bracketed one differ by more than sigma
  bool bends() const { return bracketed && std::fabs(*bracketed - parameter) > sigma; }
  // Every studied value is >= 0 (or <= 0) and the answer has the other sign: a friction, a
  // stiffness or a density below zero means no value of the studied kind reproduces the
  // measurement (its units, or the scene's vessel, mass or aeration, are the likelier cause).
  bool changesSign() const;
};

// Fits and inverts. Throws std::invalid_argument with fewer than 3 points or fewer than 2
// distinct parameter values, or when the slope is not distinguishable from zero (|b| below
// twice its standard error: the energy does not measurably depend on the parameter here).
Calibration calibrate(std::vector<CalibrationPoint> points, double measured_J,
                      double measured_se_J);

// The runs of a study folder (its variant folders holding a completed run) or the run folders
// given, in order; a folder that is neither is an error naming it.
std::vector<std::filesystem::path> ft4Runs(const std::vector<std::filesystem::path>& folders);

// The points of those runs for the measured energy's height range: parameter `parameter` from
// each run's resolved scene and its simulated energy over the same heights.
std::vector<CalibrationPoint> calibrationPoints(const std::vector<std::filesystem::path>& runs,
                                                const std::string& parameter,
                                                const MeasuredEnergy& measured);

// Readable summary (what `cosim ft4 calibrate` prints).
std::string calibrationText(const Calibration& c, const std::string& parameter);

// The calibration as JSON (ft4_calibration.json of `cosim ft4 calibrate -o`): parameter_name,
// the value and its uncertainties, the line, the measurement and the runs' points.
Json calibrationJson(const Calibration& c, const std::string& parameter);

}  // namespace cosim::analysis
