// Step 3 of the coupling step: the models evaluated over all particles. From the particle state
// and the fluid samples (same ids, same order) it makes the forcing for the particles and the
// exchange terms for the fluid.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "cosim/link/particle_data.h"
#include "plan.h"

namespace cosim::orchestrator {

struct CouplingTerms {
  link::ParticleData forcing;   // -> particles: drag_coefficient, fluid_velocity, explicit_force
  link::ParticleData exchange;  // -> fluid: drag_coefficient, transfer_coefficient
  // With a coating zone: 1 for the parcels the coating sink acts on over the interval (inside the
  // zone and found in the mesh), 0 for the others; empty without a zone (zone_passes.h).
  std::vector<char> in_zone;
};

// `lost` marks particles the fluid found in no cell: they get no fluid force and no coating.
// `dt`: the coupling interval the terms are for [s]. With models.wake (a drag with
// undisturbed_velocity 'self_disturbance_transient') every call advances each parcel's force
// history over the last interval and records this one: call it once per interval.
CouplingTerms evaluateTerms(const SceneModels& models, const Plan& plan,
                            const models::SceneConstants& constants,
                            const link::ParticleData& state, const link::ParticleData& samples,
                            const std::vector<char>& lost, double dt);

}  // namespace cosim::orchestrator
