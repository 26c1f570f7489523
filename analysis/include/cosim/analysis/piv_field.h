// The particle velocity a PIV camera sees through the front wall of a pseudo-2D vessel, from a
// run's particles.h5: the time-averaged vertical velocity of the parcels next to the wall on a
// grid of the wall's plane (x across the width, z up), and its profiles across the width at
// chosen heights. docs/calibration-validation.md section 2 describes the method.
//
// A parcel counts as seen in a snapshot when its centre lies within `depth` of the front wall
// (y - wall_y <= depth; the vessel lies at y > wall_y), or, without a fixed depth, within its
// own diameter (y - wall_y <= 2 r): the layer of parcels touching the glass and those just
// behind it. Every seen parcel of every snapshot at from <= t <= to is one sample of the cell (and
// the profile bin) its centre falls in; a cell's value is the mean vz of its samples.
//
// A profile bin's mean comes with its standard error by batch means: the snapshots are cut into
// `blocks` runs of consecutive snapshots, and the error of the ratio sum(vz) / samples is
// estimated from how the blocks' sums scatter about their samples times the mean,
// se^2 = B / (B - 1) * sum_b (S_b - mean N_b)^2 / N^2 (a block with no sample counts with 0).
// Samples of one parcel in consecutive snapshots are correlated; blocks much longer than that
// correlation (the spout's fluctuations: a few hundredths of a second) make the blocks
// independent, which the estimate assumes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "cosim/analysis/particle_file.h"

namespace cosim::analysis {

// The header line of profiles.csv (without its newline): what `cosim piv-compare` reads.
inline constexpr const char* kProfilesHeader = "height_m,x_m,vz_m_s,samples,vz_stderr_m_s";

struct PivOptions {
  double from = 0.0;                                    // [s] snapshots at from <= t <= to count
  double to = std::numeric_limits<double>::infinity();  // [s]
  std::optional<double> depth;      // [m] seen: centre within depth of the wall; none: within 2 r
  double wall_y = 0.0;              // [m] the front wall's plane y = wall_y
  double x_min = 0.0, x_max = 0.0;  // [m] the grid's extent across the width
  double z_min = 0.0, z_max = 0.0;  // [m] and up
  double cell = 0.004;              // [m] side of the square grid cells (and the profile bins)
  std::vector<double> heights;      // [m] profile heights: a band of one cell centred on each
  std::size_t blocks = 10;          // blocks of consecutive snapshots for the standard errors
};

// Running sums of vz per cell of a regular grid.
struct PivGrid {
  double x0 = 0, z0 = 0, cell = 0;  // lower-left corner and cell size [m]
  std::size_t nx = 0, nz = 0;
  std::vector<double> sum_vz;          // [iz * nx + ix]
  std::vector<std::uint64_t> samples;  // [iz * nx + ix]

  double xCentre(std::size_t ix) const { return x0 + (static_cast<double>(ix) + 0.5) * cell; }
  double zCentre(std::size_t iz) const { return z0 + (static_cast<double>(iz) + 0.5) * cell; }
  // Mean vz of cell (ix, iz); NaN without samples.
  double mean(std::size_t ix, std::size_t iz) const;
};

// One profile across the width: bins of the grid's x cells, in the band
// height - cell/2 <= z < height + cell/2.
struct PivProfile {
  double height = 0;                   // [m]
  std::vector<double> x;               // bin centres [m]
  std::vector<double> vz;              // mean vz [m/s]; NaN where no sample
  std::vector<std::uint64_t> samples;  // samples per bin
  // standard error of vz [m/s] by batch means; NaN where fewer than 2 blocks hold a sample
  std::vector<double> stderr_vz;
};

struct PivResult {
  PivGrid grid;
  std::vector<PivProfile> profiles;
  std::size_t snapshots = 0;             // snapshots used
  double first_time = 0, last_time = 0;  // [s] of the snapshots used
  std::uint64_t samples = 0;             // parcel samples seen in the grid, all snapshots
  std::size_t blocks = 0;                // blocks the standard errors were estimated with
};

// Accumulates seen parcels snapshot by snapshot (the core of pivField; usable without a file).
class PivAccumulator {
 public:
  // Throws std::invalid_argument naming the option when the grid is empty or a value is not
  // finite (cell <= 0, x_max <= x_min, depth < 0, ...).
  explicit PivAccumulator(const PivOptions& options);
  // (blocks = 0 is refused: the standard errors need at least 2, 1 gives none)
  // One snapshot: positions [n x 3], velocities [n x 3], radii [n] (radii only used without a
  // fixed depth; may be empty then).
  void add(double time, const std::vector<double>& position, const std::vector<double>& velocity,
           const std::vector<double>& radius);
  // The averages so far, with the standard errors of the profile bins over the snapshots so far.
  const PivResult& result();

 private:
  PivOptions o_;
  PivResult result_;
  std::vector<std::vector<double>> profile_sums_;
  // per snapshot, per profile bin [p * nx + ix]: sum of vz and samples (for the batch means)
  std::vector<std::vector<double>> snapshot_sums_;
  std::vector<std::vector<std::uint32_t>> snapshot_samples_;
};

// Standard error of the ratio sum(S_b) / sum(N_b) by batch means over blocks b (block sums S_b,
// sample counts N_b): sqrt(B / (B - 1) * sum_b (S_b - r N_b)^2) / sum_b N_b with r the ratio.
// NaN when fewer than 2 blocks hold a sample.
double batchMeansStandardError(const std::vector<double>& block_sums,
                               const std::vector<double>& block_samples);

// The PIV view of a recorded run. Throws std::runtime_error naming the file when it lacks
// position or velocity (or radius without a fixed depth), or when no snapshot is in
// [from, to] (saying which times it holds).
PivResult pivField(const ParticleFile& file, const PivOptions& options);

// Writes folder/grid.csv (x_m,z_m,vz_m_s,samples: one row per cell, empty vz without samples),
// folder/profiles.csv (height_m,x_m,vz_m_s,samples,vz_stderr_m_s) and folder/piv.json (the options
// and counts). The folder is created; the files are replaced atomically.
void writePiv(const PivResult& result, const PivOptions& options,
              const std::filesystem::path& folder);

}  // namespace cosim::analysis
