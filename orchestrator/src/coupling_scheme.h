// How the solvers advance over one coupling interval (step 4 of docs/design.md section 2). A
// scheme takes the terms the models made from the state at the start of the interval and returns
// each participant's Advanced reply. Another scheme (e.g. fluid first, then particles with the new
// gas) is another class here, not an edit of the coupling loop.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "coupling_terms.h"
#include "participants.h"
#include "plan.h"
#include "scenario.h"

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
  virtual std::optional<CouplingTerms> replay(const link::ParticleData& /*state*/) {
    return std::nullopt;
  }
  // `state`: the particles at the start of the interval (the terms were made from it).
  virtual AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                                 const CouplingTerms& terms) = 0;
  // The gas at the particles for the interval starting from `state`, when the scheme already
  // has it (the fluid sampled it ahead during the last interval); nullopt: sample as usual.
  virtual std::optional<wire::Samples> samplesAhead(const link::ParticleData& /*state*/) {
    return std::nullopt;
  }
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
                         const CouplingTerms& terms) override;

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
// after a resume). The placement is off by the particles' change of velocity
// over the interval, about a dt^2 / 2 (1e-7 m for a = g and dt = 1e-4 s, against cells of
// millimetres); the fluid's voidage and exchange terms follow the same placement, so mass and
// momentum stay balanced. A fluid adapter that does not answer sample_ahead is sampled as usual
// every interval.
class OverlappedScheme final : public CouplingScheme {
 public:
  OverlappedScheme(const Scenario& sc, const Plan& plan) : sc_(sc), plan_(plan) {}
  std::string name() const override { return "overlapped"; }
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const CouplingTerms& terms) override;
  std::optional<wire::Samples> samplesAhead(const link::ParticleData& state) override;

 private:
  const Scenario& sc_;
  const Plan& plan_;
  std::optional<wire::Samples> ahead_;
};

// One solver alone, for `cosim bench`: the first interval samples the fluid and evaluates the
// models as usual; every later interval replays those terms (coating increment paid once) without
// sampling, and only the named solver advances. The other one idles and costs no CPU.
//   particles alone: DEM steps under a frozen gas (K and u_f of the first interval, by id)
//   fluid alone:     CFD steps with frozen particle terms (K, k of the first interval)
class FrozenScheme final : public CouplingScheme {
 public:
  enum class Alone { particles, fluid };
  FrozenScheme(const Scenario& sc, const Plan& plan, Alone alone)
      : sc_(sc), plan_(plan), alone_(alone) {}
  std::string name() const override {
    return alone_ == Alone::particles ? "frozen-fluid" : "frozen-particles";
  }
  std::optional<CouplingTerms> replay(const link::ParticleData& state) override;
  AdvanceReplies advance(Participants& participants, const link::ParticleData& state,
                         const CouplingTerms& terms) override;
  bool evaluatesEveryStep() const override { return false; }

 private:
  const Scenario& sc_;
  const Plan& plan_;
  Alone alone_;
  std::optional<CouplingTerms> frozen_;
};

// `name`: "parallel" or "overlapped" (coupling.scheme of a run), "frozen-fluid" (particles alone)
// or "frozen-particles" (fluid alone); the last two are what `cosim bench` measures.
std::unique_ptr<CouplingScheme> makeCouplingScheme(const Scenario& sc, const Plan& plan,
                                                   const std::string& name = "parallel");

}  // namespace cosim::orchestrator
