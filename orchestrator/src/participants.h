// The participants of a run as the orchestrator sees them (the manager side of a manager /
// instance split): it starts the processes the scene needs, runs the handshake, sends messages
// and awaits the replies while watching every participant for a crash, silence or a missed
// deadline, and stops them all, cleanly or not, whatever happened.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/link/transport.h"
#include "cosim/util/errors.h"
#include "cosim/util/stop_request.h"
#include "plan.h"
#include "run_log.h"
#include "scenario.h"

namespace cosim::orchestrator {

// Why a run stopped early: who, what, and of which kind (cosim/util/errors.h: the exit code).
class RunFailure : public cosim::Error {
 public:
  RunFailure(std::string who, const std::string& what, ErrorKind kind = ErrorKind::solver)
      : cosim::Error(kind, what), participant(std::move(who)) {}
  std::string participant;  // empty: the orchestrator itself
};

// Replies by participant name.
using Replies = std::map<std::string, wire::Envelope>;

// coupling.data_path: peer: where the fluid binds its peer socket (an ipc:// address, or "tcp":
// a port of its own, said in its PeerReady) and, over CurveZMQ, each side's key pair.
struct PeerKeys {
  std::string bind;
  link::CurveKeyPair fluid, particles;
  std::string shared_memory;  // ipc://: the prefix of the peers' shared memory objects
};

// The Welcome a participant gets: its fields, options, folder, the run's clock and parameters;
// `restart_from` (empty for a fresh start) is its part of a checkpoint. With plan.peer it holds
// the peer link (`peer_endpoint`: where the fluid binds it; the particles also get the scene's
// laws and the fields each peer message carries).
wire::Welcome welcomeFor(const Scenario& sc, const Plan& plan, const ParticipantSpec& spec,
                         const std::filesystem::path& workdir,
                         const std::filesystem::path& restart_from,
                         const PeerKeys& peer = {"ipc://peer", {}, {}, {}});

class Participants {
 public:
  // stop: Ctrl-C/SIGTERM (or a caller's request) that the waits for the participants answer
  Participants(const Scenario& sc, const Plan& plan, std::string run_id, RunLog& log,
               const util::StopRequest& stop);
  ~Participants();
  Participants(const Participants&) = delete;
  Participants& operator=(const Participants&) = delete;

  // Binds the orchestrator's endpoint, prepares each participant's folder in `run_folder` and
  // starts the processes cosim launches itself.
  void start(const std::filesystem::path& run_folder);
  // Resume: the participants' folders are kept as they are, and each continues from its part
  // of `checkpoint` (Welcome.restart_from). Call before start().
  void resumeFrom(const std::filesystem::path& checkpoint) { restart_from_ = checkpoint; }
  // Where step 0 lies on the run's clock when a resume changed the coupling step (StepClock):
  // the Welcome's start_time, from which the participants count the times of steps.
  void setClockStart(double start) { clock_start_ = start; }
  // Each participant writes its part of a checkpoint into `folder`/<name>.
  void checkpoint(const std::filesystem::path& folder);
  std::vector<std::string> names() const;
  // Every participant says Hello (role, fields it provides and accepts) and gets its Welcome
  // (configuration, fields of this scene, time stepping); refuses a mismatch with the reason.
  void handshake();

  // The step and time written in the header of every message from now on; replies must be for
  // this step.
  void setClock(std::uint64_t step, double time);

  // One message to each participant named in `messages`, then the reply `reply` from each.
  Replies exchange(std::map<std::string, wire::Envelope> messages, wire::Envelope::BodyCase reply);
  // An Advance to each participant in `build` (every message built first, then sent), then their
  // Advanced replies. The participant that answered last in the previous interval is the step's
  // critical path: its message leaves first, the others' are serialised while it computes.
  using MessageBuilder = std::function<wire::Envelope()>;
  Replies advance(const std::map<std::string, MessageBuilder>& build);
  // The same for one participant.
  wire::Envelope request(const std::string& name, wire::Envelope message,
                         wire::Envelope::BodyCase reply);

  // Compute time a participant reported for an interval (kept for the summary).
  void addComputeSeconds(const std::string& name, double seconds);
  const std::map<std::string, double>& computeSeconds() const { return compute_; }
  void resetComputeSeconds() {
    compute_.clear();
    advance_wire_.clear();
  }
  // Where an Advance exchange's wall time goes, summed over the exchanges: "send" (building
  // the wire messages and handing them to ZeroMQ, one participant after the other) and, per
  // participant, "<name>_reply" (from the exchange's start to its reply's arrival). Against the
  // compute time it reported, that shows what the wire and the wake-ups cost each one.
  const std::map<std::string, double>& advanceWireSeconds() const { return advance_wire_; }

  // coupling.data_path: peer over tcp: the fluid's peer address (its PeerReady), which the
  // particles get in an Advance of zero length; empty otherwise (ipc: in their Welcome).
  const std::string& peerAddress() const { return peer_address_; }

  // Its log file, for the tail shown with a failure (empty if it is not a participant).
  std::filesystem::path logOf(const std::string& name) const;

  // clean: Shutdown and wait for Goodbye; otherwise an Error message. Then the processes are
  // stopped and the endpoint removed. Safe to call twice.
  void shutdown(bool clean);

 private:
  struct Peer;
  // own_clock: the header carries the step of the peer's last message, not the run's.
  void send(const std::string& name, wire::Envelope& env, bool own_clock = false);
  Replies await(const std::map<std::string, wire::Envelope::BodyCase>& expected,
                double timeout_seconds);
  // Checks one Hello (from the socket with routing id `route`) and answers Welcome or Refused.
  void welcome(const std::string& name, const wire::Envelope& hello, const std::string& route);
  // The participant a message comes from, if it proves it belongs to this run: it bears a
  // participant's name (Header.participant) and this run's token and, but for heartbeats, comes
  // from the socket its Hello came from. Anything else is dropped with one line per claimed
  // name in cosim.log (at most 20), a stranger's Hello answered with Refused.
  std::optional<std::string> admit(const link::Hub::Incoming& in);
  // A message of a participant of this run while the replies in `expected` are awaited: put
  // into `got` if it is one of them; heartbeats and copies of a Hello are passed over; anything
  // else is a RunFailure saying what is wrong with it.
  void take(const std::string& who, wire::Envelope& env,
            const std::map<std::string, wire::Envelope::BodyCase>& expected, Replies& got);
  // Why a participant's name was dropped, for the message when it never connects.
  std::string ignoredNote(const std::string& name) const;
  // Throws RunFailure if a participant in `expected` that has not answered yet has exited, has
  // been silent longer than the heartbeat timeout, or the wait has lasted `timeout` seconds.
  void checkAlive(const std::map<std::string, wire::Envelope::BodyCase>& expected,
                  const Replies& got, std::chrono::steady_clock::time_point start, double timeout);
  std::string connectEndpoint() const;
  // coupling.cpus: auto: the CPUs each started participant is bound to (empty map: unbound),
  // binding the orchestrator itself too; says in the run log what it chose or why not.
  std::map<std::string, std::vector<int>> cpuLayout();
  // The hub's refused connections (no keys of this run, garbage) into cosim.log.
  void logRefusals();
  // How a participant of launch: external is started, for the messages.
  std::string externalStart(const std::string& name) const;

  const Scenario& sc_;
  std::optional<double> clock_start_;  // setClockStart
  const Plan& plan_;
  std::string run_id_;
  // The folder in /dev/shm that the ranks mpirun starts here keep Open MPI's backing files in
  // (removed at the end, with what killed ranks left); empty: none made
  std::filesystem::path mpi_shm_folder_;
  std::optional<std::filesystem::path> mpiShmFolder(const ParticipantSpec& spec);
  RunLog& log_;
  // After the first request a step under way finishes (the coupler then writes a checkpoint and
  // stops), one not begun (start-up) stops at once; after the second, every wait stops.
  const util::StopRequest& stop_;
  std::unique_ptr<link::Hub> hub_;
  std::map<std::string, std::unique_ptr<Peer>> peers_;
  std::map<std::string, double> compute_;
  std::map<std::string, double> advance_wire_;
  std::map<std::string, std::chrono::steady_clock::time_point>
      arrived_;                               // replies of the exchange in progress
  std::map<std::string, double> last_reply_;  // seconds to each reply, last Advance exchange
  std::uint64_t step_ = 0;
  double time_ = 0.0;
  std::filesystem::path restart_from_;
  PeerKeys peer_;             // plan.peer: the fluid's socket for the particles, the keys
  std::string peer_address_;  // over tcp: where the fluid's peer socket listens (PeerReady)
  void preparePeerLink();
  void checkPeerReady(std::chrono::steady_clock::time_point start);
  bool stop_noted_ = false;
  bool answered_once_ = false;  // the first await of the run is over
  // when the last await ended: the time until the next one is time nobody was listened to
  std::optional<std::chrono::steady_clock::time_point> last_listened_;
  double next_wait_note_ = 15.0;  // seconds into the first await of the next "waiting" line
  void noteLongFirstWait(const std::map<std::string, wire::Envelope::BodyCase>& expected,
                         const Replies& got, std::chrono::steady_clock::time_point start,
                         double timeout);
  std::string token_;                 // this run's secret (run_token.h)
  std::filesystem::path token_file_;  // written for participants of launch: external
  std::string orchestrator_public_;   // CurveZMQ: the server's public key; else empty
  std::map<std::string, std::filesystem::path> key_files_;  // of participants of launch: external
  std::string refusal_seen_;  // the first connection the hub refused, for the messages
  std::map<std::string, std::string> ignored_;  // names claimed by dropped messages, and why
};

}  // namespace cosim::orchestrator
