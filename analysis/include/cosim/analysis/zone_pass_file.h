// zone_passes.csv: every pass of every parcel through the coating zone, recorded from the
// zone membership the laws decide at every coupling step (docs/analysis.md
// section 1). One row per pass, written when the pass ends:
//
//   parcel_id,entry_time,exit_time,coating_kg,entry,exit
//   17,0.0123,0.0151,1.25e-12,entered,left
//
//   entry_time  [s] start of the first coupling step the parcel spent in the zone
//   exit_time   [s] end of its last step in the zone (the start of the first step outside it)
//   coating_kg  [kg] precursor the parcel removed from the gas during the pass (its coating)
//   entry       "entered": it entered during the run; "at_start": it was in the zone when the run
//               started (entry_time is the run's start, the true entry is unknown)
//   exit        "left": it left the zone; "run_end": still in the zone when the run ended
//               (exit_time is the end); "deleted": the particle left the domain while in the zone
//
// Rows are written in the order the passes end (ties by parcel id) and flushed every step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cosim/link/zone_pass_tracker.h"

namespace cosim::analysis {

inline constexpr const char* kZonePassesFile = "zone_passes.csv";

// One row (cosim/link/zone_pass_tracker.h: where the passes are followed).
using ZonePass = link::ZonePass;

// Appends rows to zone_passes.csv; in append mode (resume) the existing header must match.
// Throws std::runtime_error naming the file.
class ZonePassWriter {
 public:
  enum class Mode { create, append };
  explicit ZonePassWriter(const std::filesystem::path& path, Mode mode = Mode::create);
  ~ZonePassWriter();
  ZonePassWriter(const ZonePassWriter&) = delete;
  ZonePassWriter& operator=(const ZonePassWriter&) = delete;
  // The rows of one step, then one flush.
  void write(const std::vector<ZonePass>& passes);
  std::size_t rows() const { return rows_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::size_t rows_ = 0;
};

// Reads zone_passes.csv. A last line cut short by a crash is ignored; anything else malformed
// throws std::runtime_error with file:line and what was expected.
std::vector<ZonePass> readZonePasses(const std::filesystem::path& path);

// Resume: keeps the header and the first `rows` rows (replaced atomically); throws if the file
// has fewer.
void truncateZonePasses(const std::filesystem::path& path, std::size_t rows);

}  // namespace cosim::analysis
