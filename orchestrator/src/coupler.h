// The run: prepares the run folder, starts the participants the scene needs, does the
// handshake, runs the coupling loop (docs/design.md section 2, steps 1-5, particles and fluid
// advancing at the same time), watches for crashes, silence, Ctrl-C and unphysical states,
// records, and stops everything cleanly whatever happens.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/link/particle_data.h"
#include "cosim/link/transport.h"
#include "observables.h"
#include "plan.h"
#include "processes.h"
#include "scenario.h"

namespace cosim::orchestrator {

// Why a run stopped early: who, what, and the tail of its log.
class RunFailure : public std::runtime_error {
 public:
  RunFailure(std::string who, const std::string& what)
      : std::runtime_error(what), participant(std::move(who)) {}
  std::string participant;  // empty: the orchestrator itself
};

struct RunOptions {
  bool quiet = false;            // no progress line
  std::filesystem::path output;  // overrides scenario output.folder
  bool overwrite = false;        // reuse an existing run folder
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
};

// Set by SIGINT/SIGTERM handlers; the loop stops cleanly at the next check.
extern std::atomic<int> g_stop_signal;

class Coupler {
 public:
  Coupler(Scenario scenario, RunOptions options);
  ~Coupler();
  RunResult run();

  // Called after each coupling step with the current state, coating of that step included
  // (tests and monitors).
  std::function<void(double time, const link::ParticleData& state)> on_step;

 private:
  struct Peer;
  void prepareFolder();
  void startParticipants();
  void handshake();
  std::map<std::string, wire::Envelope> await(
      const std::map<std::string, wire::Envelope::BodyCase>& expected, double timeout_seconds);
  void send(const std::string& peer, wire::Envelope& env);
  void checkState(const link::ParticleData& state, const std::string& where);
  void shutdown(bool clean);
  // One time-series row: to timeseries.csv and to the in-memory series the observables read.
  void appendRow(double time, const std::vector<double>& row);
  // A particle snapshot of heldState(), every output.interval and when forced.
  void record(double time, bool force);
  // state_ with the pending coating credit added: what the particles hold at time_.
  link::ParticleData heldState() const;
  void writeSummary(const RunResult& r, const std::string& status);

  Scenario sc_;
  RunOptions opt_;
  SceneModels models_;
  Plan plan_;
  std::string run_id_;
  std::filesystem::path folder_;
  std::unique_ptr<link::Hub> hub_;
  std::map<std::string, std::unique_ptr<Peer>> peers_;
  std::uint64_t step_ = 0;
  double time_ = 0.0;
  link::ParticleData state_;
  std::map<std::int64_t, double> pending_credit_;  // precursor removed, to credit as coating
  std::map<std::string, double> totals_;
  std::map<std::string, double> wall_;
  std::map<std::string, double> phase_;  // wall seconds per phase of the coupling step
  std::vector<ObservableValue> observables_;
  std::vector<double> series_time_;
  std::map<std::string, std::vector<double>>
      series_;  // compute seconds per participant (kept after shutdown)
  double next_output_ = 0.0;
  struct Recorders;
  std::unique_ptr<Recorders> rec_;
};

}  // namespace cosim::orchestrator
