#include "cosim/models/force/pressure_gradient.h"

#include <numbers>

#include "cosim/models/input_checks.h"

namespace cosim::models {

void PressureGradientForce::addForces(const ParcelBatch& p, const SceneConstants& c,
                                      double* force) const {
  const std::string owner = "force model '" + name() + "'";
  validateConstants(owner, c);
  checkInputs(owner, requiredFields(), p, c);
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) continue;  // no fluid, no force
    const double r = p.radius[i];
    const double V = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    for (int j = 0; j < 3; ++j) force[3 * i + j] -= V * p.pressure_gradient[3 * i + j];
  }
  checkOutputs(owner, "force", force, 3 * p.n);
}

}  // namespace cosim::models
