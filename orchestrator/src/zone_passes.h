// Exact passes of every parcel through the coating zone (docs/analysis.md, "zone_passes.csv").
// The coupler decides at the start of every coupling step which parcels are in the zone (the
// zone's shape, and found in the fluid's mesh): exactly those get a transfer coefficient, so
// exactly those take precursor from the gas over the step. This recorder follows that membership
// from step to step: a pass opens at the start of the first step a parcel spends in the zone and
// closes at the start of the first step it spends outside (its last step's end). It adds to each
// open pass the precursor its parcel removed over the step (the pass's coating) and writes every
// closed pass to RUN/zone_passes.csv. Its state (the rows written, who is in the zone since when
// with how much coating) is part of a checkpoint, so that a resumed run writes the same file as
// an uninterrupted one.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include "cosim/analysis/zone_pass_file.h"
#include "cosim/link/particle_data.h"

namespace cosim::orchestrator {

class ZonePassRecorder {
 public:
  struct OpenPass {
    double entry_time = 0;  // [s]
    double coating = 0;     // [kg] precursor removed since the entry
    bool at_start = false;  // in the zone when the run started
  };
  struct State {
    std::size_t rows = 0;                   // rows of zone_passes.csv
    std::map<std::int64_t, OpenPass> open;  // parcels in the zone now
    double coating_outside = 0;             // [kg] removed by parcels in no pass: 0 by design
  };

  // A new run: creates RUN/zone_passes.csv; passes open at the first update are `at_start`.
  void start(const std::filesystem::path& run_folder);
  // Resume: cuts zone_passes.csv back to the checkpoint's rows and continues from its state.
  void resume(const std::filesystem::path& run_folder, State state);

  // The membership decided for the step starting at `time`: in_zone[i] for parcel ids[i].
  // Parcels that left the zone close their pass at `time`; parcels that entered open one.
  void update(double time, const std::vector<std::int64_t>& ids, const std::vector<char>& in_zone);
  // The same from the ids of the parcels in the zone, sorted (the peer path's account).
  void updateInside(double time, std::vector<std::int64_t> inside);
  // The fluid's per-parcel precursor_removed over the step joins the open passes.
  void credit(const link::ParticleData& fluid_results);
  // Particles deleted in the step ending at `time` close their pass there.
  void leave(const std::vector<std::int64_t>& deleted_ids, double time);
  // End of the run at `time`: every open pass is written with exit run_end (a pass opened at
  // `time` itself, by a step that never finished, is dropped).
  void close(double time);

  State state() const { return {writer_ ? writer_->rows() : 0, open_, coating_outside_}; }
  double coatingOutsidePasses() const { return coating_outside_; }

 private:
  void flush();
  std::unique_ptr<analysis::ZonePassWriter> writer_;
  std::map<std::int64_t, OpenPass> open_;
  std::vector<analysis::ZonePass> closed_;  // rows of the current step, written by flush()
  double coating_outside_ = 0;
  bool first_update_ = false;
};

}  // namespace cosim::orchestrator
