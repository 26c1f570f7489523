// Checkpoints of the whole coupled state (docs/restarts.md). RUN/checkpoints/<time>/ holds one
// folder per participant (what its adapter's Checkpoint wrote: LIGGGHTS restart file, OpenFOAM
// time folder, ...) and orchestrator.json, the coupler's own state: time, step, the coating owed,
// the balance totals, the monitors, the recorders' positions, the open zone passes. A checkpoint is
// written under a temporary name and renamed when every part is on disk: it is complete or absent.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cosim/link/coating_ledger.h"
#include "cosim/link/particle_data.h"
#include "cosim/models/drag/wake_buildup.h"
#include "stability.h"
#include "zone_passes.h"

namespace cosim::orchestrator {

// The run's clock: coupling step k ends at start + k dt (link::stepTime). `start` is
// coupling.start_time until a resume changes coupling.dt: the steps done keep their numbers and
// times, and `start` becomes where step 0 would lie at the new dt (the checkpoint's time minus
// its steps times dt), so that the step numbers the participants check run on.
struct StepClock {
  double start = 0.0;  // [s]
  double dt = 0.0;     // [s]
  double time(std::uint64_t k) const;
  std::uint64_t stepsTo(double end) const;  // the step that ends at `end`, rounded
};

struct CoupledState {
  std::uint64_t step = 0;  // coupling steps done
  double time = 0.0;       // [s]
  // The clock the steps were counted on; absent in a checkpoint of an older cosim (then the
  // scene's coupling.start_time and coupling.dt: clockOf)
  std::optional<StepClock> clock;
  link::CoatingLedger::Balance balance;
  std::map<std::int64_t, double> pending;  // coating owed, by parcel id
  std::map<std::string, double> totals;
  StepMonitor::State monitor;
  std::size_t initial_count = 0;
  bool initial_row_written = false;
  std::size_t series_rows = 0;            // rows of timeseries.csv at the checkpoint
  double next_output = 0.0;               // next particle snapshot [s]
  double wall_seconds = 0.0;              // wall time of the run so far
  std::map<std::string, double> phases;   // wall seconds per phase so far
  std::map<std::string, double> compute;  // compute seconds per participant so far
  std::string scene;                      // the resolved scenario it was written with (YAML)
  // Digest of each particle field at the checkpoint ("ids" and every field name -> 16 hex
  // digits): a resume checks that the particle participant read back exactly this state.
  std::map<std::string, std::string> particle_digest;
  // Scenes with a coating zone: the open passes and the rows of zone_passes.csv. Absent in a
  // checkpoint written without pass recording (an older cosim, or a scene without a zone).
  std::optional<ZonePassRecorder::State> zone_passes;
  // Scenes with undisturbed_velocity 'self_disturbance_transient': every parcel's force history
  // (cosim/models/drag/wake_buildup.h), so that a resumed run continues it bit for bit.
  std::optional<models::WakeBuildup::State> wake;
  // Scheme 'overlapped': where the fluid sampled the gas for the next interval (the particles at
  // the last interval's start moved by velocity dt), every sampled field; a resumed run samples
  // the gas there first (coupling_scheme.h). Absent for the other schemes.
  std::optional<link::ParticleData> sample_ahead;
};

// FNV-1a digests of the particle state, one per field (and "ids"), over the values' bytes in
// id order: equal digests mean the same state to the bit.
std::map<std::string, std::string> particleDigest(const link::ParticleData& state);

// The fields whose digests differ between a checkpoint and the state read back ("" when they
// agree or the checkpoint has none).
std::vector<std::string> digestDifferences(const std::map<std::string, std::string>& saved,
                                           const std::map<std::string, std::string>& now);

class CheckpointStore {
 public:
  explicit CheckpointStore(const std::filesystem::path& run_folder);
  // A fresh temporary folder for a checkpoint at `time`, with one empty folder per participant.
  std::filesystem::path begin(double time, const std::vector<std::string>& participants) const;
  // Writes the coupler's state, renames the temporary folder to its final name and removes all
  // but the newest `keep` checkpoints. Returns the final folder.
  std::filesystem::path commit(const std::filesystem::path& partial, const CoupledState& state,
                               int keep) const;
  // The newest complete checkpoint, if any.
  std::optional<std::filesystem::path> newest() const;
  // Every complete checkpoint, oldest first.
  std::vector<std::filesystem::path> all() const;
  // The complete checkpoint at `time` (to a relative 1e-9), if any.
  std::optional<std::filesystem::path> at(double time) const;
  // Moves every complete checkpoint newer than `kept` into checkpoints/superseded/ (a resume
  // from an older one makes them another history; they are kept, never removed) and returns
  // where they went.
  std::vector<std::filesystem::path> setAsideAfter(const std::filesystem::path& kept) const;
  // "0.1 s, 0.12 s" (the times of all()), or "none".
  std::string listTimes() const;

 private:
  std::filesystem::path dir_;
};

CoupledState readCoupledState(const std::filesystem::path& checkpoint);

// The clock a checkpoint's steps were counted on.
StepClock clockOf(const CoupledState& saved);

// A resume may make the coupling step smaller (or larger), to go through a stiff stretch: the
// DEM step coupling.dt / coupling.dem_steps must stay what the particle solver's script and
// restart hold. The reason a change of coupling.dt or coupling.dem_steps cannot be honoured
// ("" when it can, or when neither changed).
std::string refusedStepChange(const YAML::Node& saved, const YAML::Node& now);

// A new step from `time` whose steps do not fall on start_time + k dt: the records' times from
// there on lie off the grid of the run's output times (a warning, with what keeps them on it).
std::optional<std::string> offTheStepGrid(double start_time, double time, double dt);

// Keys of the scene whose values differ between a checkpoint's scene and the one to resume with,
// as "key: old -> new", leaving out what a resumed run may change (end time, output, checkpoint,
// transport, checks, observables, description, timeouts).
std::vector<std::string> sceneDifferences(const YAML::Node& saved, const YAML::Node& now);

}  // namespace cosim::orchestrator
