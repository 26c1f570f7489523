// Step 3 of the coupling step: the laws of a scene evaluated over parcels. From the particle
// state and the fluid samples (same ids, same order) it makes the forcing for the particles and
// the exchange terms for the fluid. The orchestrator calls it over every parcel (the central
// data path); a particle participant may call it over its own parcels (docs/design.md
// section 5): the terms of a parcel depend on that parcel's state and samples only.
#pragma once

#include <cstdint>
#include <vector>

#include "cosim/link/particle_data.h"
#include "cosim/models/parcels.h"
#include "cosim/models/scene_models.h"

namespace cosim::models {

struct CouplingTerms {
  link::ParticleData forcing;   // -> particles: drag_coefficient, fluid_velocity, explicit_force
  link::ParticleData exchange;  // -> fluid: drag_coefficient, transfer_coefficient
  // With a coating zone: 1 for the parcels the coating sink acts on over the interval (inside the
  // zone and found in the mesh), 0 for the others; empty without a zone
  // (orchestrator/src/zone_passes.h).
  std::vector<char> in_zone;
};

// `coating`: the scene transfers precursor to the parcels (the transfer coefficient, the zone).
// `lost` marks particles the fluid found in no cell: they get no fluid force and no coating.
// `dt`: the coupling interval the terms are for [s]. With models.wake (a drag with
// undisturbed_velocity 'self_disturbance_transient') every call advances each parcel's force
// history over the last interval and records this one: call it once per interval.
// `threads`: the parcels split into up to that many contiguous parts of at least 8,192, each
// on a thread of its own (the same numbers as on one: a parcel's terms are its own), when the
// scene's laws allow it (SceneModels::splittable); the wake's history stays on this thread.
CouplingTerms evaluateTerms(const SceneModels& models, bool coating,
                            const SceneConstants& constants, const link::ParticleData& state,
                            const link::ParticleData& samples, const std::vector<char>& lost,
                            double dt, unsigned threads = 1);

}  // namespace cosim::models
