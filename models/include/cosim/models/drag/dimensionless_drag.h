// Shared evaluation loop of the drag laws. A law supplies its dimensionless drag
//   f(eps, Re) = K_particle / (3 pi mu d_real)
// (1 in the Stokes limit) and this loop returns per parcel K = cg^3 * 3 pi mu d_real * f.
// Inputs are checked before the loop and outputs after it (see input_checks.h).
#pragma once

#include <numbers>
#include <string>

#include "cosim/models/input_checks.h"
#include "cosim/models/model.h"
#include "cosim/models/parcel_state.h"

namespace cosim::models {

// Fields every voidage-dependent drag law reads.
inline std::vector<std::string> denseDragFields() {
  return {"radius", "velocity", "fluid_velocity", "voidage", "fluid_density", "fluid_viscosity"};
}

inline std::string dragOwner(const std::string& name) { return "drag law '" + name + "'"; }

template <class DimensionlessDrag>
void evaluateDrag(const DragLaw& law, const ParcelBatch& p, const SceneConstants& c, double* K,
                  DimensionlessDrag&& f) {
  const std::string owner = dragOwner(law.name());
  validateConstants(owner, c);
  checkInputs(owner, law.requiredFields(), p, c);
  const double cg3 = c.cg * c.cg * c.cg;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) {
      K[i] = 0.0;
      continue;
    }
    const ParcelState s = parcelState(p, c, i);
    K[i] = cg3 * 3.0 * std::numbers::pi * s.mu * s.d * f(s.eps, s.Re);
  }
  checkOutputs(owner, "drag coefficient K", K, p.n);
}

}  // namespace cosim::models
