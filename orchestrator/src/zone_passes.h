// RUN/zone_passes.csv (docs/analysis.md, "zone_passes.csv"): every pass of every parcel through
// the coating zone, one row per pass, written as the passes close. On the central data path the
// recorder follows the zone membership itself (a link::ZonePassTracker: the coupler decides at
// the start of every coupling step which parcels are in the zone); on the peer path the particle
// session keeps the tracker and the recorder writes the passes it reports (write()). Its state
// (the rows written, and on the central path who is in the zone since when with how much
// coating) is part of a checkpoint, so that a resumed run writes the same file as an
// uninterrupted one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "cosim/analysis/zone_pass_file.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/zone_pass_tracker.h"

namespace cosim::orchestrator {

class ZonePassRecorder {
 public:
  using OpenPass = link::ZonePassTracker::OpenPass;
  struct State {
    std::size_t rows = 0;                   // rows of zone_passes.csv
    std::map<std::int64_t, OpenPass> open;  // parcels in the zone now (central path)
    double coating_outside = 0;             // [kg] removed by parcels in no pass: 0 by design
  };

  // A new run: creates RUN/zone_passes.csv; passes open at the first update are `at_start`.
  void start(const std::filesystem::path& run_folder);
  // Resume: cuts zone_passes.csv back to the checkpoint's rows and continues from its state.
  void resume(const std::filesystem::path& run_folder, State state);

  // The central path: link::ZonePassTracker's calls, each writing the passes it closed.
  void update(double time, const std::vector<std::int64_t>& ids, const std::vector<char>& in_zone);
  void credit(const link::ParticleData& fluid_results);
  void leave(const std::vector<std::int64_t>& deleted_ids, double time);
  void close(double time);
  // The peer path: passes the particle session closed, written as they come.
  void write(const std::vector<analysis::ZonePass>& passes);

  State state() const;
  double coatingOutsidePasses() const { return tracker_.coatingOutsidePasses(); }

 private:
  void flush();
  std::unique_ptr<analysis::ZonePassWriter> writer_;
  link::ZonePassTracker tracker_;
};

}  // namespace cosim::orchestrator
