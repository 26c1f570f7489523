// constants: the scene constants every coupling law sees (coarse graining, voidage clamp,
// gravity, Schmidt number) and the particle material the stability checks use.
#pragma once

#include <vector>

#include "cosim/models/parcels.h"
#include "scenario/context.h"

namespace cosim::orchestrator {

// Is-a SceneConstants, so that it goes to the models as it is; the material rides along.
struct ConstantsSection : models::SceneConstants {
  // Particle material, optional: used by the stability checks (Rayleigh time, relaxation time).
  struct Material {
    double particle_density = 0.0;  // [kg/m3]; 0 = unknown
    double youngs_modulus = 0.0;    // [Pa]; 0 = unknown
    double poisson_ratio = 0.3;
  } material;

  static const std::vector<KeySpec>& keys();
};

ConstantsSection parseConstants(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator
