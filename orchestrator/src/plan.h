// What a scene needs: which participants to start and which fields each packet carries,
// derived from the configured models. A scene without coating sends no precursor fields; a scene
// without fluid forces starts no fluid participant.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cosim/models/scene_models.h"
#include "scenario.h"

namespace cosim::orchestrator {

struct Plan {
  bool fluid = false;    // start the fluid participant
  bool coating = false;  // mass transfer: species in the fluid, coating on particles
  // coupling.data_path: peer with a fluid: the particles sample the gas and evaluate the laws
  // themselves (peer_link.h); the orchestrator sends the schedule and the coating owed
  bool peer = false;
  // particles participant
  std::vector<std::string> particles_send;     // state it reports
  std::vector<std::string> particles_receive;  // forcing it takes
  // fluid participant, per message
  std::vector<std::string> sample_state;           // Sample: particle state to locate and sample
  std::vector<std::string> sample_returns;         // Samples: the gas at the parcels
  std::vector<std::string> fluid_advance_terms;    // Advance: exchange terms
  std::vector<std::string> fluid_advance_returns;  // Advanced: per-parcel results
  // and over both messages (negotiated at the handshake)
  std::vector<std::string> fluid_send;     // sample_returns + fluid_advance_returns
  std::vector<std::string> fluid_receive;  // sample_state + fluid_advance_terms
  std::vector<std::string> notes;          // what was left out and why (shown to the user)
};

// The laws of the scene's models: section (its plugins were loaded when it was read).
models::SceneModels makeModels(const Scenario& sc);
// Throws ScenarioError when an observable names a particle field, time-series column or total
// this plan does not record (checkObservables), so that `cosim validate` catches the typo.
Plan makePlan(const Scenario& sc, const models::SceneModels& m);

// The columns of timeseries.csv after "time", in order, for this plan.
std::vector<std::string> timeSeriesColumns(const Plan& plan);
// The names of the run totals (totals.<name>) a run with this plan can have.
std::vector<std::string> runTotals(const Plan& plan);
// Every observable against what the plan records; ScenarioError naming file, line and key.
void checkObservables(const Scenario& sc, const Plan& plan);

}  // namespace cosim::orchestrator
