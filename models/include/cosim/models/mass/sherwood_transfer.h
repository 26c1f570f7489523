// Shared evaluation of the mass-transfer laws (paper Eq. 7 times cg^3):
//   k = cg^3 K_m rho_f pi d^2,  K_m = Sh D / d,  D = mu / (rho_f Sc)   =>  k = cg^3 pi mu d Sh / Sc
// A law supplies Sh(eps, Re, Sc). dm/dt = k Y; the coating-zone mask is applied by the caller.
#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "cosim/models/input_checks.h"
#include "cosim/models/model.h"
#include "cosim/models/parcel_state.h"

namespace cosim::models {

inline std::vector<std::string> massTransferFields() {
  return {"radius", "velocity", "fluid_velocity", "voidage", "fluid_density", "fluid_viscosity"};
}

template <class Sherwood>
void evaluateTransfer(const MassTransferLaw& law, const ParcelBatch& p, const SceneConstants& c,
                      double* k, Sherwood&& sh) {
  const std::string owner = "mass transfer law '" + law.name() + "'";
  validateConstants(owner, c);
  checkInputs(owner, law.requiredFields(), p, c);
  const double cg3 = c.cg * c.cg * c.cg;
  const double sc = c.schmidt;
  const double sc13 = std::cbrt(sc);
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) {
      k[i] = 0.0;
      continue;
    }
    const ParcelState s = parcelState(p, c, i);
    k[i] = cg3 * std::numbers::pi * s.mu * s.d * sh(s.eps, s.Re, sc13) / sc;
  }
  checkOutputs(owner, "transfer coefficient k", k, p.n);
}

}  // namespace cosim::models
