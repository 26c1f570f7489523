// Stokes drag: F = 3 pi mu d_real (u_f - v) per real particle, K = cg^3 3 pi mu d_real.
// Voidage is not used (single particle in unbounded fluid, Re -> 0).
#include "cosim/models/drag/stokes.h"

#include <numbers>

#include "cosim/models/drag/dimensionless_drag.h"

namespace cosim::models {

void StokesDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  const std::string owner = dragOwner(name());
  validateConstants(owner, c);
  checkInputs(owner, requiredFields(), p, c);
  const double cg3 = c.cg * c.cg * c.cg;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) {
      K[i] = 0.0;
      continue;
    }
    K[i] = cg3 * 3.0 * std::numbers::pi * p.fluid_viscosity[i] * realDiameter(p.radius[i], c);
  }
  checkOutputs(owner, "drag coefficient K", K, p.n);
}

}  // namespace cosim::models
