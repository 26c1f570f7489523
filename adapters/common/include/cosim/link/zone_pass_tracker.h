// Exact passes of every parcel through the coating zone (docs/analysis.md, "zone_passes.csv").
// At the start of every coupling step the laws decide which parcels are in the zone (the zone's
// shape, and found in the fluid's mesh): exactly those get a transfer coefficient, so exactly
// those take precursor from the gas over the step. The tracker follows that membership from step
// to step: a pass opens at the start of the first step a parcel spends in the zone and closes at
// the start of the first step it spends outside (its last step's end); each open pass adds up
// the precursor its parcel removed over its steps (the pass's coating). Closed passes wait in
// closed() until taken.
//
// Who keeps it: the orchestrator on the central data path (ZonePassRecorder writes what it
// closes to RUN/zone_passes.csv); the particle session on the peer path, which sends what it
// closes to the orchestrator after every interval (wire::PeerLedger.passes). Its state is part
// of a checkpoint, so that a resumed run records the same passes as an uninterrupted one.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cosim/link/particle_data.h"

namespace cosim::link {

// One pass of one parcel: a row of zone_passes.csv.
struct ZonePass {
  enum class Exit { left, run_end, deleted };
  std::int64_t parcel_id = 0;
  double entry_time = 0;   // [s]
  double exit_time = 0;    // [s]
  double coating = 0;      // [kg]
  bool at_start = false;   // in the zone when the run started: the entry is not observed
  Exit exit = Exit::left;  // run_end or deleted: the exit is not observed
  double duration() const { return exit_time - entry_time; }
  bool complete() const { return !at_start && exit == Exit::left; }  // entry and exit observed
};

// The end of coupling step k (k steps after `start`), rounded to 12 significant digits so that
// 2453 steps of 1e-4 s end at 0.2453 s and not at 0.24530000000000002: the time every record of
// the run carries, computed the same way wherever it is kept.
double stepTime(double start, double dt, std::uint64_t k);

class ZonePassTracker {
 public:
  struct OpenPass {
    double entry_time = 0;  // [s]
    double coating = 0;     // [kg] precursor removed since the entry
    bool at_start = false;  // in the zone when the run started
  };
  struct State {
    std::map<std::int64_t, OpenPass> open;  // parcels in the zone now
    double coating_outside = 0;             // [kg] removed by parcels in no pass: 0 by design
    bool started = false;                   // the first membership is known (a resumed run)
  };

  // The membership decided for the step starting at `time`: in_zone[i] for parcel ids[i].
  // Parcels that left the zone close their pass at `time`; parcels that entered open one (at the
  // run's first update: `at_start`).
  void update(double time, const std::vector<std::int64_t>& ids, const std::vector<char>& in_zone);
  // The same from the ids of the parcels in the zone, sorted.
  void updateInside(double time, std::vector<std::int64_t> inside);
  // The per-parcel precursor_removed over the step joins the open passes.
  void credit(const ParticleData& removed);
  // Particles deleted in the step ending at `time` close their pass there.
  void leave(const std::vector<std::int64_t>& deleted_ids, double time);
  // End of the run at `time`: every open pass closes with exit run_end (a pass opened at `time`
  // itself, by a step that never finished, is dropped).
  void close(double time);

  // The passes closed since the last take, in the order they closed (ties by parcel id).
  std::vector<ZonePass> takeClosed();
  const std::vector<ZonePass>& closed() const { return closed_; }

  State state() const { return {open_, coating_outside_, started_}; }
  void restore(State s);
  double coatingOutsidePasses() const { return coating_outside_; }

 private:
  std::map<std::int64_t, OpenPass> open_;
  std::vector<ZonePass> closed_;
  double coating_outside_ = 0;
  bool started_ = false;
};

}  // namespace cosim::link
