#include "coupling_scheme.h"

namespace cosim::orchestrator {

AdvanceReplies ParallelScheme::advance(Participants& participants, const CouplingTerms& terms) {
  std::map<std::string, wire::Envelope> messages;
  {
    auto* a = messages["particles"].mutable_advance();
    a->set_dt(sc_.coupling.dt);
    a->set_substeps(sc_.coupling.dem_steps);
    terms.forcing.select(plan_.particles_receive).toWire(*a->mutable_terms());
  }
  if (plan_.fluid) {
    auto* a = messages["fluid"].mutable_advance();
    a->set_dt(sc_.coupling.dt);
    a->set_substeps(1);
    terms.exchange.select(plan_.fluid_advance_terms).toWire(*a->mutable_terms());
  }
  auto replies = participants.exchange(std::move(messages), wire::Envelope::kAdvanced);
  AdvanceReplies r;
  r.particles = replies.at("particles").advanced();
  if (plan_.fluid) r.fluid = replies.at("fluid").advanced();
  return r;
}

std::unique_ptr<CouplingScheme> makeCouplingScheme(const Scenario& sc, const Plan& plan) {
  return std::make_unique<ParallelScheme>(sc, plan);
}

}  // namespace cosim::orchestrator
