// Stokes drag: F = 3 pi mu d_real (u_f - v) per real particle, K = cg^3 3 pi mu d_real.
// Voidage is not used (single particle in unbounded fluid).
#include "cosim/models/drag/stokes.h"

#include <cmath>
#include <numbers>

namespace cosim::models {

void StokesDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  const double cg3 = c.cg * c.cg * c.cg;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double d_real = 2.0 * p.radius[i] / c.cg;
    K[i] = cg3 * 3.0 * std::numbers::pi * p.fluid_viscosity[i] * d_real;
  }
}

}  // namespace cosim::models
