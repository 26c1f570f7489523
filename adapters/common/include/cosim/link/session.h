// Participant side of the protocol: handshake, step checks, heartbeat, error reporting.
// An adapter implements Solver and calls runParticipant(); MPI adapters call it on rank 0 and
// forward to their other ranks themselves. C++17.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/curve_keys.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/peer_link.h"
#include "cosim/link/transport.h"
#include "cosim/util/errors.h"

namespace cosim::link {

// The environment variable through which the orchestrator hands its run token to the
// participants it starts (never on the command line, which every user can read with ps).
inline constexpr const char* kRunTokenVariable = "COSIM_RUN_TOKEN";

// Command line every adapter understands (the orchestrator passes these).
struct ParticipantOptions {
  std::string endpoint;  // --endpoint
  std::string name;      // --name
  std::string run_id;    // --run-id (checked against the Welcome header when given)
  // The run's secret, carried by every message: read from --token-file, else from the
  // environment variable COSIM_RUN_TOKEN (set by cosim for the participants it starts).
  std::string token;
  // CurveZMQ keys for a tcp:// link: read from --key-file, else from the environment variable
  // COSIM_CURVE_KEYS (set by cosim for the participants it starts); empty: no encryption.
  CurveClientKeys curve;
  int heartbeat_ms = 500;
  int handshake_timeout_ms = 30000;
  int command_timeout_ms = 600000;  // orchestrator silent this long: give up
  // After the Welcome: no connection to the orchestrator's socket for this long means the
  // orchestrator is gone (killed, its host unreachable); the participant then stops.
  int orchestrator_gone_ms = 3000;
  // `cosim validate` asks an adapter whether it accepts a scene without starting a run:
  // --check-options FILE names a Welcome (binary protobuf, as the run would send it, its
  // workdir a templated copy of the case files) and --ranks the MPI ranks the run would use.
  // --endpoint and --name are then not needed (checkSceneOptions).
  std::string check_options;
  int check_ranks = 1;
  // --options-reference: print the adapter's scenario options (participants.NAME.options) as a
  // Markdown table and exit; --endpoint and --name are then not needed.
  bool options_reference = false;
  // --workdir DIR: a folder of the participant's own on its node, for a participant that does
  // not see the run folder (no shared filesystem, docs/cluster.md). The case files and restart
  // come in the Welcome and are written here; checkpoints are written here and sent back.
  // Empty: the Welcome's workdir in the run folder is used, as on one machine.
  std::string workdir;
  // The adapter's command line, parsed with CLI11: --endpoint, --name, --run-id, --token-file,
  // --key-file, --heartbeat-ms, --command-timeout (seconds), --check-options FILE, --ranks N,
  // --workdir DIR,
  // --help. `--help` prints `about` and the options to stdout and returns nullopt (the adapter then
  // exits 0). Arguments it does not know are left in `rest` in their order (e.g. OpenFOAM's
  // -parallel, -case DIR), or ignored when rest is null. Throws std::runtime_error with the usage
  // when --endpoint or --name is missing, a value is malformed or the token file cannot be read.
  static std::optional<ParticipantOptions> parse(int argc, char** argv, const std::string& about,
                                                 std::vector<std::string>* rest = nullptr);
};

struct Capabilities {
  wire::Role role = wire::ROLE_UNSPECIFIED;
  std::string adapter;
  std::vector<std::string> provides;
  std::vector<std::string> accepts;
};

// What an adapter implements. Throw std::exception with a clear message on any failure: the
// session sends it to the orchestrator as wire::Error and exits non-zero.
class Solver {
 public:
  virtual ~Solver() = default;
  virtual Capabilities capabilities() const = 0;
  // After the Welcome: read configuration, set up the solver.
  virtual void configure(const wire::Welcome& welcome) = 0;
  // Fluid only: sample the requested fields (welcome.send) at the given particles.
  virtual void sample(const ParticleData& particles, ParticleData& out,
                      std::vector<std::int64_t>& lost_ids) {
    (void)particles;
    (void)out;
    (void)lost_ids;
    throw InputError("this adapter does not sample fluid fields");
  }
  // Advance one coupling interval (dt == 0: only report the current state). `terms` are
  // cmd.terms() unpacked: an adapter may read either (on every data path the session keeps them
  // the same).
  virtual void advance(const wire::Advance& cmd, const ParticleData& terms, wire::Advanced& out,
                       ParticleData& state) = 0;
  // Writes everything the solver needs to continue from this moment into the folder `path`
  // (created by the orchestrator; the participant's own part of a checkpoint) and returns the
  // files written. Called between coupling steps.
  virtual std::vector<std::string> checkpoint(const std::string& path) {
    (void)path;
    throw InputError("this adapter cannot write checkpoints");
  }
  // After configure, when the run resumes: continue from what checkpoint(path) wrote.
  virtual void restore(const std::string& path) {
    (void)path;
    throw InputError("this adapter cannot resume from a checkpoint");
  }
  virtual void finish() {}
};

// What an adapter checks of a scene before any solver starts (--check-options): its options,
// the files they name, the MPI ranks. Throws std::runtime_error with the reason on refusal.
using SceneCheck = std::function<void(const wire::Welcome& welcome, int ranks)>;

// The --check-options mode: reads options.check_options, runs `check`, prints "options
// accepted" (exit 0) or the reason to stderr (exit 2). No MPI, no solver, no connection.
int checkSceneOptions(const ParticipantOptions& options, const SceneCheck& check);

// True when the command line asks for --check-options or --options-reference (for adapters that
// must decide before MPI_Init whether to start MPI at all).
bool checkOptionsRequested(int argc, char** argv);

// Coupling scheme `overlapped`: the particles of Advance.sample_ahead where they will be after
// dt, position + velocity dt (positions as they are when no velocity is given). The session
// samples there after the fluid's advance; a fluid adapter may use the same positions to
// prepare that sampling during its step (they are the same numbers, bit for bit).
ParticleData predictedAt(ParticleData at, double dt);

// The solver's Sample of `in` as the Samples message (lost ids, the time it took).
// With `shared`, the samples' values go through the peers' shared memory (shared_arrays.h).
void sampleInto(Solver& solver, const ParticleData& in, wire::Samples& out,
                SharedArrayWriter* shared = nullptr);

// Runs the whole participant life: connect, Hello, Welcome, command loop, Goodbye.
// Returns the process exit code (0 on a clean Shutdown). `peer_terms`: a particle adapter's
// coupling laws for coupling.data_path: peer (peer_link.h); without them such a scene is refused
// with the reason. A fluid adapter needs nothing for it.
int runParticipant(Solver& solver, const ParticipantOptions& options,
                   PeerTerms* peer_terms = nullptr);

// Lower-level pieces, for tests and custom loops.
class Session {
 public:
  Session(const ParticipantOptions& options, const Capabilities& caps);
  ~Session();
  // Sends Hello (again every second until answered: a stranger holding the participant's name
  // at the orchestrator's socket only delays it), waits for Welcome. Throws PeerError if refused.
  wire::Welcome handshake();
  // Next command from the orchestrator. Heartbeats are sent in the background meanwhile.
  // Checks version, run id and step order: a command whose step is behind the last one seen
  // or more than one ahead is answered with Error and a ProtocolError is thrown. Throws
  // PeerError when the orchestrator is gone (options.orchestrator_gone_ms without a connection)
  // or the connection to it was lost and made again since the Welcome (a network cut longer
  // than ZeroMQ's heartbeat: what was in flight may be lost, so the run cannot go on).
  wire::Envelope nextCommand();
  // For a process that is nothing but this participant (runParticipant): when the orchestrator
  // is gone while the solver is busy in a step, the heartbeat thread ends the process with the
  // message and exit code 3 after another 5 s, instead of letting the step finish first.
  void exitProcessWhenOrphaned() { exit_when_orphaned_ = true; }
  // Fills the header (step/time of the current command) and sends; PeerError, as nextCommand,
  // if the connection was lost and made again.
  void reply(wire::Envelope& env);
  void sendError(const std::string& message, const std::string& where = "");
  // Throws PeerError when the orchestrator is gone (as nextCommand would): for waits on
  // something else than the orchestrator (the peer link).
  void checkOrchestrator();
  const std::string& runId() const { return run_id_; }
  std::uint64_t step() const { return step_; }
  double time() const { return time_; }

 private:
  void fillHeader(wire::Header* h) const;
  void receiveFiles(wire::Welcome& welcome) const;
  // PeerError if the command channel has connected again since the Welcome.
  void checkStillConnected();
  ParticipantOptions options_;
  Capabilities caps_;
  std::unique_ptr<Channel> channel_;
  std::string run_id_;
  std::uint64_t step_ = 0;
  double time_ = 0.0;
  bool any_command_ = false;
  std::atomic<bool> stop_heartbeat_{false};
  std::atomic<bool> exit_when_orphaned_{false};
  // Set by the heartbeat thread when the orchestrator is gone; gone_message_ is written before.
  std::atomic<bool> orchestrator_gone_{false};
  std::string gone_message_;
  int reconnections_at_welcome_ = 0;  // of the command channel
  std::thread heartbeat_;
};

}  // namespace cosim::link
