// How the solvers advance over one coupling interval (step 4 of docs/design.md section 2). A
// scheme takes the terms the models made from the state at the start of the interval and returns
// each participant's Advanced reply. Another scheme (e.g. fluid first, then particles with the new
// gas) is another class here, not an edit of the coupling loop.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "cosim/models/coupling_terms.h"
#include "participants.h"
#include "plan.h"
#include "scenario.h"
#include "terms_recording.h"

namespace cosim::orchestrator {

struct AdvanceReplies {
  std::optional<wire::Advanced> particles;  // absent when only the fluid advances (cosim bench)
  std::optional<wire::Advanced> fluid;      // scenes with a fluid participant
};

class CouplingScheme {
 public:
  virtual ~CouplingScheme() = default;
  virtual std::string name() const = 0;
  // Terms this scheme replays for the interval starting from `state`, instead of sampling the
  // fluid and evaluating the models; nullopt (the default): sample and evaluate as usual.
  virtual std::optional<models::CouplingTerms> replay(const link::ParticleData& /*state*/) {
    return std::nullopt;
  }
  // `state`: the particles at the start of the interval (the terms were made from it).
  virtual AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                                 const models::CouplingTerms& terms) = 0;
  // The gas at the particles for the interval starting from `state`, when the scheme already
  // has it (the fluid sampled it ahead during the last interval); nullopt: sample as usual.
  virtual std::optional<wire::Samples> samplesAhead(Participants& /*participants*/,
                                                    const link::ParticleData& /*state*/) {
    return std::nullopt;
  }
  // Where the scheme's samples for the next interval were taken, when they differ from the
  // particles' state (the overlapped scheme's prediction): a checkpoint keeps it, so that a
  // resumed run samples the gas where the run that never stopped did. nullopt: nothing to keep.
  virtual std::optional<link::ParticleData> samplingAhead() const { return std::nullopt; }
  // A resumed run's first interval samples the gas there (what samplingAhead() gave).
  virtual void resumeSamplingAt(link::ParticleData /*where*/) {}
  // False when later intervals replay earlier terms: the zone membership is then not known at
  // every step, and no zone passes are recorded.
  virtual bool evaluatesEveryStep() const { return true; }
};

// Explicit coupling, both solvers at the same time: the particles advance dem_steps DEM steps
// under the forcing while the fluid advances one CFD step with the exchange terms, both from the
// state at the start of the interval. The interval then costs the slower of the two.
class ParallelScheme final : public CouplingScheme {
 public:
  ParallelScheme(const Scenario& sc, const Plan& plan) : sc_(sc), plan_(plan) {}
  std::string name() const override { return "parallel"; }
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const models::CouplingTerms& terms) override;

 private:
  const Scenario& sc_;
  const Plan& plan_;
};

// Both solvers at the same time as in ParallelScheme, and the next interval's sampling inside
// the fluid's step instead of between the intervals: the fluid's Advance carries the particles
// at the start of the interval (Advance.sample_ahead); after its CFD step the fluid places them
// at position + velocity dt and returns the gas there (Advanced.ahead), while the particles are
// still advancing. The next interval uses those samples when the particles are the same (same
// ids in the same order) and none was predicted outside the mesh, else it samples as usual (an
// insertion, a deletion, a parcel about to bounce off a wall, the first step, the first step
// after a resume without samplingAhead() in its checkpoint). A checkpoint keeps where the fluid
// sampled ahead (samplingAhead()), and the first interval after a resume samples the gas (restored
// to the bit) there, so the resumed run continues as the one that never stopped. The placement
// is off by the particles' change of velocity
// over the interval, about a dt^2 / 2 (1e-7 m for a = g and dt = 1e-4 s, against cells of
// millimetres); the fluid's voidage and exchange terms follow the same placement, so mass and
// momentum stay balanced. A fluid adapter that does not answer sample_ahead is sampled as usual
// every interval.
class OverlappedScheme final : public CouplingScheme {
 public:
  OverlappedScheme(const Scenario& sc, const Plan& plan) : sc_(sc), plan_(plan) {}
  std::string name() const override { return "overlapped"; }
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const models::CouplingTerms& terms) override;
  std::optional<wire::Samples> samplesAhead(Participants& participants,
                                            const link::ParticleData& state) override;
  std::optional<link::ParticleData> samplingAhead() const override;
  void resumeSamplingAt(link::ParticleData where) override { resume_at_ = std::move(where); }

 private:
  const Scenario& sc_;
  const Plan& plan_;
  std::optional<wire::Samples> ahead_;
  link::ParticleData sent_;  // the sampled fields at the last interval's start (buffers reused)
  std::optional<link::ParticleData> resume_at_;
};

// The rank-to-rank data path (coupling.data_path: peer, cosim/link/peer_link.h): both solvers at
// the same time as in ParallelScheme (or sampling ahead as in OverlappedScheme, between the two
// participants), but the particles sample the gas from the fluid and evaluate the laws over their
// own parcels; each gets an Advance without per-parcel terms, the
// particles' carrying only the coating owed (the terms' forcing: a coating_increment of the
// parcels owed any). `report_first`: the first interval's particles also send back the gas
// samples and the forcing, for the checks of a run's first step (not after a resume).
class PeerScheme final : public CouplingScheme {
 public:
  PeerScheme(const Scenario& sc, const Plan& plan, bool report_first)
      : sc_(sc), plan_(plan), report_(report_first) {}
  std::string name() const override { return sc_.coupling.scheme + ", data path peer"; }
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const models::CouplingTerms& terms) override;

 private:
  const Scenario& sc_;
  const Plan& plan_;
  bool report_;
};

// One solver alone, for `cosim bench`; only the named solver advances, the other idles and
// costs no CPU.
//   particles alone: DEM steps under the forcing of the recorded coupled run (K, u_f, explicit
//                    force and coating increment of interval k, by id)
//   fluid alone:     CFD steps with the recorded particle terms (K, k of interval k)
// Given a recording (the coupled stage's TermsRecording), interval k replays its interval k (the
// fluid alone samples and evaluates its first interval, which places the parcels in its cells), so
// the solver alone sees what it saw coupled and does the same work (a bed held under the first
// interval's gas moves differently and costs the DEM more or less than the coupled bed). Past the
// recording's end its last interval's terms are held; without one the first interval samples the
// fluid and evaluates the models as usual and every later one replays those terms (the coating
// increment paid once in both cases).
class FrozenScheme final : public CouplingScheme {
 public:
  enum class Alone { particles, fluid };
  FrozenScheme(const Scenario& sc, const Plan& plan, Alone alone,
               std::shared_ptr<const TermsRecording> recording = nullptr)
      : sc_(sc), plan_(plan), alone_(alone), recording_(std::move(recording)) {}
  std::string name() const override {
    return alone_ == Alone::particles ? "frozen-fluid" : "frozen-particles";
  }
  std::optional<models::CouplingTerms> replay(const link::ParticleData& state) override;
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const models::CouplingTerms& terms) override;
  bool evaluatesEveryStep() const override { return false; }
  std::size_t replayedIntervals() const { return replayed_; }  // taken from the recording

 private:
  const Scenario& sc_;
  const Plan& plan_;
  Alone alone_;
  std::shared_ptr<const TermsRecording> recording_;
  std::size_t interval_ = 0;  // intervals started
  std::size_t replayed_ = 0;
  std::optional<models::CouplingTerms> frozen_;
};

// `name`: "parallel" or "overlapped" (coupling.scheme of a run), "frozen-fluid" (particles alone)
// or "frozen-particles" (fluid alone); the last two are what `cosim bench` measures, replaying
// `recording` when one is given. "parallel" with plan.peer is the PeerScheme (`fresh`: a new run,
// not a resume).
std::unique_ptr<CouplingScheme> makeCouplingScheme(
    const Scenario& sc, const Plan& plan, const std::string& name = "parallel",
    std::shared_ptr<const TermsRecording> recording = nullptr, bool fresh = true);

}  // namespace cosim::orchestrator
