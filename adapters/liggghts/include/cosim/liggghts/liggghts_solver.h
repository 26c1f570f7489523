// LiggghtsSolver: the particles participant backed by an embedded LIGGGHTS.
//
// MPI: rank 0 runs the protocol session (cosim::link::runParticipant) and broadcasts every
// command (as the serialized protobuf message) to the other ranks, which wait in serve();
// the terms of an Advance go to each rank for its own parcels only (by the rank each parcel was
// on at the last state). All ranks then execute the command collectively; the state is gathered
// to rank 0 sorted by id.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/liggghts/adapter_options.h"
#include "cosim/liggghts/engine.h"
#include "cosim/link/session.h"

namespace cosim::liggghts {

class LiggghtsSolver : public cosim::link::Solver {
 public:
  explicit LiggghtsSolver(MPI_Comm comm);
  ~LiggghtsSolver() override;

  // rank 0: cosim::link::Solver
  cosim::link::Capabilities capabilities() const override;
  void configure(const cosim::wire::Welcome& welcome) override;
  void advance(const cosim::wire::Advance& cmd, const cosim::link::ParticleData& terms,
               cosim::wire::Advanced& out, cosim::link::ParticleData& state) override;
  std::vector<std::string> checkpoint(const std::string& path) override;
  // The restart file was read while configuring (Engine::resumeScript): nothing left to do.
  void restore(const std::string& /*path*/) override {}
  void finish() override;

  // ranks > 0: execute broadcast commands until Finish/Quit or an error. Returns the exit code.
  int serve();
  // rank 0, after runParticipant: lets waiting ranks go if the session ended without Shutdown.
  void releaseOtherRanks();
  // An error left the MPI ranks out of step: the process must MPI_Abort.
  bool mustAbort() const { return must_abort_; }

 private:
  // kAdvanceOwnTerms: an Advance without terms, each rank's terms following (scatterTerms)
  enum Op : int {
    kConfigure = 1,
    kAdvance = 2,
    kCheckpoint = 3,
    kFinish = 4,
    kQuit = 5,
    kAdvanceOwnTerms = 6
  };
  void broadcast(Op op, const std::string& payload);
  template <class F>
  void collective(F&& f);

  void doConfigure(const cosim::wire::Welcome& welcome);
  // own: this rank's terms (kAdvanceOwnTerms); else those of cmd, every rank all of them
  void doAdvance(const cosim::wire::Advance& cmd, const Terms* own = nullptr);
  static Terms termsOf(cosim::link::ParticleData terms);
  // rank 0: the rank that holds each of these parcels, by the last state; PeerError naming ids
  // LIGGGHTS does not have
  std::vector<int> ranksOf(const std::vector<std::int64_t>& ids) const;
  Terms scatterTerms(const Terms* all, const std::vector<int>* to);
  std::vector<std::string> doCheckpoint(const std::string& path);
  void doFinish();
  void checkTimestep();
  void warnIfDumpsOffTheRunClock(const cosim::wire::Welcome& welcome) const;

  MPI_Comm comm_;
  int rank_ = 0;
  std::unique_ptr<Engine> engine_;
  AdapterOptions options_;
  std::vector<std::string> send_;
  bool ranks_released_ = false;  // no other rank waits for a command any more
  bool must_abort_ = false;
  // dt check: smallest radius already judged (re-judged when smaller particles appear)
  double checked_radius_ = 0;
  std::optional<TimestepReport> dt_report_;
  bool dt_reported_ = false;
  // rank 0: ids and coating mass of the last report (for inserted/deleted ids)
  // Coating mass of every particle at the last report, by id ascending (as state() sorts them)
  std::vector<std::int64_t> last_ids_;
  std::vector<double> last_coating_;
  bool reported_once_ = false;
  State last_state_;
};

}  // namespace cosim::liggghts
