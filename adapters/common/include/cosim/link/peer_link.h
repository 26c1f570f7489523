// The rank-to-rank data path with one rank a side (coupling.data_path: peer; docs/design.md
// section 5): the per-parcel data of an interval goes between the two participants directly.
// The orchestrator sends each an Advance without per-parcel terms; then
//   particles -> fluid   Sample     the parcels' state (Welcome.peer.sample_state)
//   fluid -> particles   Samples    the gas at the parcels
//   particles            the scene's laws over their parcels (PeerTerms), the forcing kept
//   particles -> fluid   Advance    the exchange terms; both solvers advance
//   fluid -> particles   Advanced   the fluid's per-parcel results (precursor_removed)
// and each answers the orchestrator with its report (the particles with their count and the
// parcels that came and went, and with a coating their part of the ledger: the coating owed to
// each parcel, paid into its forcing, and the zone passes, of which the orchestrator gets the
// running totals and the passes closed, wire::PeerInterval.ledger). The session runs this around
// the Solver calls every adapter implements, so any adapter built on cosim_link has the path.
// C++17.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/coating_ledger.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/shared_arrays.h"
#include "cosim/link/transport.h"
#include "cosim/link/zone_pass_tracker.h"

namespace cosim::link {

class Solver;

// The particle side's coupling laws over its own parcels: what the orchestrator's step 3 does
// over every parcel on the central path (cosim::models::evaluateTerms). The protocol library
// knows no model: an adapter that can take part in the peer path passes one of these to
// runParticipant (cosim/link/peer_terms.h in cosim_models_wire has the one built from the scene's
// laws).
class PeerTerms {
 public:
  virtual ~PeerTerms() = default;
  // The scene's laws and constants (Welcome.peer.models); ProtocolError names a bad field.
  virtual void configure(const wire::PeerLink& link) = 0;
  struct Terms {
    ParticleData forcing;       // -> this participant's solver
    ParticleData exchange;      // -> the fluid
    std::vector<char> in_zone;  // with a coating zone: the parcels the sink acts on
  };
  // `state` and `samples` hold the same ids in the same order; `lost`: in no cell.
  virtual Terms evaluate(const ParticleData& state, const ParticleData& samples,
                         const std::vector<char>& lost, double dt) = 0;
  // The laws' own history between intervals (a transient wake), for checkpoints: empty when
  // there is none. restoreState gets what saveState gave, bit for bit.
  virtual std::string saveState() const { return {}; }
  virtual void restoreState(const std::string& bytes) { (void)bytes; }
};

// Who is talking: what every peer message carries and is checked for (Header).
struct PeerIdentity {
  std::string run_id;
  std::string token;
  std::string name;  // this participant's
};

// Called while waiting for the peer: throws (PeerError) when the orchestrator is gone.
using PeerWatch = std::function<void()>;

// The fluid's side: binds Welcome.peer.bind and serves one interval at a time.
class FluidPeer {
 public:
  // `orchestrator`: the orchestrator's address; over tcp the peer socket binds an ephemeral port
  // on the local address that reaches it (the one network both sides are known to share).
  FluidPeer(const wire::PeerLink& link, PeerIdentity who, int timeout_ms,
            const std::string& orchestrator);
  // Where the peer socket listens (tcp: the PeerReady the session sends the orchestrator).
  const std::string& endpoint() const { return hub_->endpoint(); }
  // The orchestrator's Advance `cmd` (dt > 0): answers the particles' Sample, advances the
  // solver with the exchange terms of their Advance and sends them its per-parcel results.
  // `out` gets the solver's report without per-parcel data.
  void interval(Solver& solver, const wire::Advance& cmd, std::uint64_t step, double time,
                wire::Advanced& out, const PeerWatch& watch);

 private:
  wire::Envelope await(wire::Envelope::BodyCase expected, std::uint64_t step,
                       const PeerWatch& watch);
  void send(wire::Envelope& env, std::uint64_t step, double time);
  PeerIdentity who_;
  int timeout_ms_;
  std::unique_ptr<Hub> hub_;
  std::string route_;  // the particles' routing id, from their first valid message
  std::unique_ptr<SharedArrays> shared_;  // Welcome.peer.shared_memory: the values through it
  SharedArrayWriter* sharedOut() const { return shared_ ? &shared_->out : nullptr; }
  SharedArrayReader* sharedIn() const { return shared_ ? &shared_->in : nullptr; }
};

// The particles' side: connects to the fluid, evaluates the laws, keeps the last state.
class ParticlePeer {
 public:
  ParticlePeer(const wire::PeerLink& link, const wire::Welcome& welcome, PeerTerms& terms,
               PeerIdentity who, int timeout_ms);
  // The state the particles last reported (any Advance, dt = 0 included): where the next
  // interval samples the gas, as the orchestrator would from the same reply.
  void setState(ParticleData state) { state_ = std::move(state); }
  // Over tcp: the fluid's address, from Advance.peer_connect (again with the same: nothing).
  void connect(const std::string& endpoint);
  // The orchestrator's Advance `cmd` (dt > 0, no per-parcel terms): samples the gas, evaluates
  // the laws, pays the coating owed into the forcing, sends the fluid its terms, advances the
  // solver, waits for the fluid's results and books them (the ledger, the zone passes). `out`
  // and `state` as Solver::advance gives them, with out.peer filled.
  void interval(Solver& solver, const wire::Advance& cmd, std::uint64_t step, double time,
                wire::Advanced& out, ParticleData& state, const PeerWatch& watch);
  PeerTerms& terms() { return terms_; }
  // The checks the orchestrator makes of a state it is not sent (Advance.state_ids_only): every
  // field a finite number, no parcel faster than Welcome.peer.max_particle_speed; ProtocolError
  // naming the parcel otherwise.
  void checkState(const ParticleData& state) const;
  // coupling.scheme overlapped: where the fluid sampled the gas ahead (the parcels at the last
  // interval's start, moved by velocity dt), for a checkpoint: a resumed run samples it there
  // again (restoreAhead), so that it continues as the run that never stopped. Empty: none.
  std::string aheadBytes() const;
  void restoreAhead(const std::string& bytes);

  // An Advance of zero length, before the solver's: with pay_owed, everything owed as the
  // coating_increment of the parcels of the last state (the run's last uptake); else nothing.
  ParticleData zeroLengthTerms(const wire::Advance& cmd);
  // ... and after it: the payment delivered, with close_passes the open passes closed at the end
  // of step `step`, and the ledger's report into out.peer.ledger.
  void afterZeroLength(const wire::Advance& cmd, std::uint64_t step, wire::Advanced& out);
  // A state as the orchestrator records it: the coating owed added to each parcel's coating.
  ParticleData held(const ParticleData& state) const { return ledger_.held(state); }
  // The ledger and the open passes for a checkpoint (a wire::PeerLedgerState), and back.
  std::string ledgerBytes() const;
  void restoreLedger(const std::string& bytes);
  bool keepsLedger() const { return link_.coating(); }

 private:
  wire::Envelope request(wire::Envelope& env, wire::Envelope::BodyCase expected, std::uint64_t step,
                         double time, const PeerWatch& watch);
  // The gas at the parcels where the last reply left them: sampled ahead at the last interval's
  // end when the parcels are the same ones and none was placed outside the mesh (the central
  // path's overlapped rules), else sampled now.
  wire::Samples gasAtParcels(std::uint64_t step, double time, const PeerWatch& watch);
  // Everything owed, paid as the coating_increment of `forcing`'s parcels.
  void payOwed(ParticleData& forcing);
  // The fluid's per-parcel removal, of the parcels that took any.
  ParticleData removal(const wire::Advanced& results) const;
  // The interval's uptake booked: passes opened and closed at `start`, the removal owed and
  // added to the open passes, parcels deleted by `end` gone from both.
  void book(const std::vector<char>& in_zone, const ParticleData& taken, const wire::Advanced& out,
            double start, double end);
  void report(wire::PeerInterval& account);
  void totals(wire::PeerLedger& ledger) const;  // the ledger's running totals
  wire::PeerLink link_;
  std::vector<std::string> sample_fields_;   // Welcome.peer.sample_state
  std::vector<std::string> forcing_fields_;  // Welcome.receive
  PeerTerms& terms_;
  PeerIdentity who_;
  int timeout_ms_;
  std::unique_ptr<Channel> channel_;
  std::string connected_to_;
  std::unique_ptr<SharedArrays> shared_;  // Welcome.peer.shared_memory: the values through it
  SharedArrayWriter* sharedOut() const { return shared_ ? &shared_->out : nullptr; }
  SharedArrayReader* sharedIn() const { return shared_ ? &shared_->in : nullptr; }
  ParticleData state_;
  std::optional<wire::Samples> ahead_;        // the gas where the parcels are now, sampled ahead
  std::optional<wire::FieldSet> ahead_sent_;  // the parcels ahead_ was sampled from (moved by
  double ahead_dt_ = 0;                       // velocity ahead_dt_: where it was sampled)
  std::optional<ParticleData> resume_at_;     // a resume's: sample there first
  CoatingLedger ledger_;                      // the coating owed to the parcels, the totals
  std::optional<ZonePassTracker> passes_;     // Welcome.peer.zone_passes
  double start_time_ = 0;                     // Welcome.start_time: the run's step times
  double dt_ = 0;                             // Welcome.cfd_dt
};

// The name of the file a particle participant keeps its laws' history in, in its checkpoint part.
inline constexpr const char* kPeerTermsFile = "peer_terms.bin";
// ... and where it had the gas sampled ahead (coupling.scheme overlapped): a wire::FieldSet.
inline constexpr const char* kPeerAheadFile = "peer_ahead.pb";
// ... and, with a coating, its part of the coating ledger and the open zone passes: a
// wire::PeerLedgerState.
inline constexpr const char* kPeerLedgerFile = "peer_ledger.pb";

}  // namespace cosim::link
