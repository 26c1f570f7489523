// The run: one coupling loop over the pieces that each own one concept (docs/design.md):
//   Participants    start, handshake, send and await, watch, shut down (participants.h)
//   CouplingScheme  how both solvers advance over an interval (coupling_scheme.h)
//   CoatingLedger   coating owed and paid, the precursor balance (cosim/link/coating_ledger.h)
//   RunRecord       run folder, time series, snapshots, summary (run_record.h)
//   StepMonitor     what no physics allows, checked every step (stability.h)
//   ZonePassRecorder every parcel's passes through the coating zone (zone_passes.h)
// Whatever happens (a crash, silence, Ctrl-C, an unphysical state), everything is stopped and
// what was recorded so far stays, with a summary that says why the run ended.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "checkpoints.h"
#include "cosim/link/coating_ledger.h"
#include "cosim/link/particle_data.h"
#include "coupling_scheme.h"
#include "observables.h"
#include "participants.h"
#include "plan.h"
#include "progress.h"
#include "run_log.h"
#include "run_record.h"
#include "scenario.h"
#include "stability.h"
#include "zone_passes.h"

namespace cosim::orchestrator {

struct RunOptions {
  bool quiet = false;            // no progress line
  std::filesystem::path output;  // overrides scenario output.folder
  bool overwrite = false;        // reuse an existing run folder
  std::string
      scheme;  // makeCouplingScheme; empty: the scene's coupling.scheme (bench: frozen ones)
  // cosim bench: the phase and compute timings start after this many steps of this invocation
  // (after the resumed step for a resume). Unset: they cover the whole run, resumes included.
  std::optional<std::uint64_t> untimed_steps;
  std::filesystem::path resume;  // continue the run in this folder from its newest checkpoint
  // ... or from the one at this time (cosim resume --from); newer ones are set aside
  std::optional<double> resume_from;
  // cosim bench: the coupled stage appends every interval's terms to `record_terms` (outside the
  // timed phases); the solver-alone stages replay `replay_terms` (FrozenScheme).
  std::shared_ptr<TermsRecording> record_terms;
  std::shared_ptr<const TermsRecording> replay_terms;
  // Ctrl-C/SIGTERM (commands/common.cpp's processStop()) or a caller's own request: the run
  // stops after its step with a checkpoint, a second request at once. nullptr: never asked.
  const util::StopRequest* stop = nullptr;
};

struct RunResult {
  int exit_code = 0;
  std::filesystem::path folder;
  std::string message;
  std::size_t steps = 0;
  double wall_seconds = 0;
  link::ParticleData final_state;
  std::map<std::string, double> totals;  // mass balance and other accumulated scalars
  std::vector<ObservableValue> observables;
  std::map<std::string, double> phase_seconds;    // per phase of the step, after untimed_steps
  std::map<std::string, double> compute_seconds;  // per participant, after untimed_steps
  std::uint64_t timed_steps = 0;                  // steps the timings cover
  double time = 0;                                // [s] the simulated time the run reached
  bool unstable_step = false;                     // stopped by checks.max_courant (step_retreat.h)
};

class Coupler {
 public:
  Coupler(Scenario scenario, RunOptions options);
  ~Coupler();
  RunResult run();

  // Called after each coupling step with the current state, coating of that step included
  // (tests and monitors).
  std::function<void(double time, const link::ParticleData& state)> on_step;

 private:
  // Step 0: the particles report their initial state; the checks before the run.
  void reportInitialState();
  // Resume: the state of the newest checkpoint; returns the steps already done.
  std::uint64_t resumeFromCheckpoint();
  void refuseWhatItCannotHonour(const CoupledState& saved,
                                const std::filesystem::path& checkpoint) const;
  // Every participant's part and the coupler's own state, under checkpoints/<time>/.
  void writeCheckpoint();
  bool checkpointDue(bool last) const;
  // The five steps of one coupling interval (docs/design.md section 2).
  void beginStep(std::uint64_t k);
  models::CouplingTerms termsOfStep();  // steps 2 and 3, or what the scheme replays
  // The fluid's samples checked against the particles; `lost` marks those in no cell.
  link::ParticleData samplesOf(const wire::Samples& samples, std::vector<char>& lost);
  link::ParticleData sampleFluid(std::vector<char>& lost);
  models::CouplingTerms evaluateModels(const link::ParticleData& samples,
                                       const std::vector<char>& lost);
  AdvanceReplies advanceBoth(const models::CouplingTerms& terms);
  void takeParticleState(const wire::Advanced& particles);
  void takePeerAccount(const wire::PeerInterval& account);
  void takePeerLedger(const wire::PeerLedger& ledger);
  void takeParticleChanges(const wire::Advanced& particles);
  void takeFluidResults(const wire::Advanced& fluid);
  void creditAndRecord(const AdvanceReplies& replies, bool last);
  // The coating owed after the last interval, paid with an Advance of zero length.
  void flushCredit();
  // An Advance of zero length: the particles take `terms` (none, or coating owed) and report
  // their state into state_; on the peer path they may also pay what they owe or close the
  // open zone passes (the run's end).
  enum class ZeroLength { state, pay_owed, close_passes };
  void reportParticleState(const link::ParticleData& terms, ZeroLength what = ZeroLength::state);
  void closePeerPasses();
  void wholeState();
  void finishRun();
  std::string howToContinue(const std::string& status, std::uint64_t steps_done) const;
  void resetTimings();
  // Scenes with a coating zone whose membership is decided at every step (not cosim bench).
  bool recordsZonePasses() const;
  // Every pass still open is written with the time of the last finished step.
  void recordStoppedState();
  void closeZonePasses(std::uint64_t steps_done);

  void check(const link::ParticleData& state, const std::string& where) const;
  void refuseOrWarn(const StabilityReport& report);
  std::string describe(const RunFailure& failure) const;
  analysis::Summary summarize(const RunResult& r, const std::string& status) const;

  // Wall seconds per phase of the coupling step.
  struct Phases {
    std::map<std::string, double> seconds;
    std::chrono::steady_clock::time_point tick;
    void start() { tick = std::chrono::steady_clock::now(); }
    void lap(const char* phase);
    void skip() { start(); }  // the time since the last lap counts in no phase
  };

  Scenario sc_;
  RunOptions opt_;
  const util::StopRequest& stop_;  // opt_.stop, or one never requested
  RunLog log_;
  models::SceneModels models_;
  Plan plan_;
  std::string run_id_;
  RunRecord record_;
  Participants participants_;
  std::unique_ptr<CouplingScheme> scheme_;
  link::CoatingLedger ledger_;
  StepMonitor monitor_;
  std::optional<ZonePassRecorder> passes_;
  bool passes_closed_ = false;       // the peer path: the particles closed the open passes
  double peer_coating_outside_ = 0;  // the peer path: the particles' count (PeerLedger)
  Progress* progress_ = nullptr;

  std::optional<CheckpointStore> checkpoints_;
  double next_checkpoint_ = 0.0;
  // Free bytes on the run folder's disk when coupling started (simulated time, bytes), and
  // whether the disk's filling has been warned of (writeCheckpoint)
  std::optional<std::pair<double, double>> disk_;
  // Bytes free on the run folder's disk (nullopt if it cannot be asked)
  std::optional<double> freeBytes() const;
  bool disk_warned_ = false;
  double wall_before_ = 0.0;  // wall seconds of the run before it was resumed
  bool resume_accepted_ = false;
  // The checkpoint a resume started from and its step: a failure before the run got past it
  // says which other checkpoints there are (the one it started from may be what failed).
  std::filesystem::path resumed_from_;
  std::uint64_t resumed_step_ = 0;
  bool unreadable_checkpoint_ = false;  // its orchestrator.json could not be read

  StepClock clock_;  // when each step ends (a resume may change the step)
  std::uint64_t nsteps_ = 0;
  bool courant_stop_ = false;  // RunResult::unstable_step
  std::uint64_t step_ = 0;
  double time_ = 0.0;
  link::ParticleData state_;
  bool state_partial_ = false;  // peer path: state_ holds the parcels' ids only, sorted
  std::size_t initial_count_ = 0;
  double reported_dt_over_rayleigh_ = 0.0;  // the particle participant's, 0 if it reports none
  bool initial_row_written_ = false;
  std::map<std::string, double> totals_;
  Phases phases_;
  std::chrono::steady_clock::time_point wall0_;
};

}  // namespace cosim::orchestrator
