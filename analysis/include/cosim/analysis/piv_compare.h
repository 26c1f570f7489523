// Simulated PIV profiles against measured ones: the mean absolute error of the vertical particle
// velocity per profile (height) and per region, the upward core and the downward sides, as the
// paper reports its validation. docs/calibration-validation.md section 2 gives the CSV format.
//
// Profile CSV (measured, and cosim piv's profiles.csv): a header line naming at least the columns
// height_m, x_m and vz_m_s (any order, more columns allowed), then one row per point: the height
// of the profile above the bottom [m], the position across the width [m, the vessel's centre
// at 0] and the vertical velocity [m/s]; an empty vz_m_s is a point without data. Lines
// starting with '#' are comments. An optional column vz_stderr_m_s holds the standard error of
// each vz (cosim piv writes it; a measurement may give its own): with it the comparison also
// says what mean absolute error the sampling noise alone would give.
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cosim::analysis {

struct ProfilePoint {
  double height = 0, x = 0, vz = 0;                             // [m], [m], [m/s]; vz NaN: no data
  double stderr_vz = std::numeric_limits<double>::quiet_NaN();  // [m/s]; NaN: not known
};

// Reads a profile CSV. Throws std::runtime_error naming the file, line and column on any
// malformed line (missing column, not a number, duplicate header name).
std::vector<ProfilePoint> readProfileCsv(const std::filesystem::path& path);

struct PivCompareOptions {
  // Core = upward region. Without a band: the points where the MEASURED vz > 0 (the sides are
  // those with vz <= 0). With a band [x0, x1]: the points with x0 <= x <= x1.
  std::optional<std::pair<double, double>> core_band;
  double height_tolerance = 1e-6;  // [m] a measured and a simulated height are the same profile
};

struct MaeEntry {
  double mae = 0;          // [m/s] mean |v_sim - v_measured|; NaN with no point
  std::size_t points = 0;  // points compared
  // The mean absolute error the sampling noise alone gives where the two agree: the mean over
  // the points whose simulated standard error is known of sqrt(2 / pi) * sqrt(se_sim^2 +
  // se_measured^2) (a measured error not given counts as 0); NaN when no point has one.
  double noise_mae = 0;          // [m/s]
  std::size_t noise_points = 0;  // points with a known simulated standard error
};

struct ProfileComparison {
  double height = 0;  // [m]
  MaeEntry all, core, sides;
  std::size_t without_simulation = 0;  // measured points outside the simulated profile's data
};

struct PivComparison {
  std::vector<ProfileComparison> profiles;  // in the order of the measured heights
  MaeEntry all, core, sides;                // over every profile's points
};

// The simulated vz at each measured x: linear interpolation between the two nearest simulated
// points with data; beyond the outermost ones the nearest value if it lies within one spacing
// of the simulated points, else the point counts as without simulation. Throws
// std::runtime_error when a measured height has no simulated profile (listing the simulated
// heights) or a simulated profile has no data.
PivComparison comparePiv(const std::vector<ProfilePoint>& simulated,
                         const std::vector<ProfilePoint>& measured,
                         const PivCompareOptions& options);

}  // namespace cosim::analysis
