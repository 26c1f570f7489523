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
  wire::Advanced particles;
  std::optional<wire::Advanced> fluid;  // scenes with a fluid participant
};

class CouplingScheme {
 public:
  virtual ~CouplingScheme() = default;
  virtual std::string name() const = 0;
  virtual AdvanceReplies advance(Participants& participants, const CouplingTerms& terms) = 0;
};

// Explicit coupling, both solvers at the same time: the particles advance dem_steps DEM steps
// under the forcing while the fluid advances one CFD step with the exchange terms, both from the
// state at the start of the interval. The interval then costs the slower of the two.
class ParallelScheme final : public CouplingScheme {
 public:
  ParallelScheme(const Scenario& sc, const Plan& plan) : sc_(sc), plan_(plan) {}
  std::string name() const override { return "parallel"; }
  AdvanceReplies advance(Participants& participants, const CouplingTerms& terms) override;

 private:
  const Scenario& sc_;
  const Plan& plan_;
};

std::unique_ptr<CouplingScheme> makeCouplingScheme(const Scenario& sc, const Plan& plan);

}  // namespace cosim::orchestrator
