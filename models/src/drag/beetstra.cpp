#include "cosim/models/drag/beetstra.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "cosim/models/drag/dimensionless_drag.h"
#include "cosim/models/drag/radl_sundaresan.h"

namespace cosim::models {

double beetstraF(double eps, double Re) {
  const double phi = 1.0 - eps;
  const double eps2 = eps * eps;
  const double low_re = 10.0 * phi / eps2 + eps2 * (1.0 + 1.5 * std::sqrt(phi));
  // Inertial term with numerator and denominator multiplied by Re^b, b = (1 + 4 phi)/2, so that
  // Re = 0 gives 0 instead of 0 * inf:
  //   0.413/(24 eps^2) (Re/eps + 3 eps phi Re + 8.4 Re^0.657) Re^b / (Re^b + 10^(3 phi))
  // (the powers of Re from one logarithm: one log and three exp instead of three pow)
  const double lnRe = Re > 0.0 ? std::log(Re) : -std::numeric_limits<double>::infinity();
  const double reb = std::exp((0.5 + 2.0 * phi) * lnRe);
  const double inertial = 0.413 / (24.0 * eps2) *
                          (Re / eps + 3.0 * eps * phi * Re + 8.4 * std::exp(0.657 * lnRe)) * reb /
                          (reb + std::exp(3.0 * std::numbers::ln10 * phi));
  return low_re + inertial;
}

BeetstraDrag::BeetstraDrag(const Parameters& p) {
  p.rejectUnknown({"filtered", "parcel_size_factor", "k", "particle_density",
                   "reference_fluid_density", "reference_fluid_viscosity"});
  filtered_ = p.flag("filtered", false);
  // The parcel-size factor exp(k (1 - cg)) is its own choice, off unless asked for (as in
  // CFDEMcoupling-PFM): giving k alone also switches it on.
  parcel_factor_ = p.flag("parcel_size_factor", p.has("k"));
  k_ = p.has("k") ? p.number("k", 0.0, 10.0) : 0.05;
  if (p.has("k") && !parcel_factor_) {
    throw ModelError(p.owner() +
                     ": parameter 'k' is the exponent of the parcel-size factor; "
                     "remove it or set parcel_size_factor: true");
  }
  if (filtered_) {
    if (!p.has("particle_density")) {
      throw ModelError(p.owner() +
                       ": parameter 'particle_density' [kg/m3] is required with "
                       "filtered: true (the Radl & Sundaresan correction needs the terminal "
                       "velocity of one real particle), e.g. particle_density: 1750");
    }
    particle_density_ = p.positive("particle_density");
    if (p.has("reference_fluid_density") != p.has("reference_fluid_viscosity")) {
      throw ModelError(p.owner() +
                       ": give both 'reference_fluid_density' [kg/m3] and "
                       "'reference_fluid_viscosity' [Pa s], or neither (then each parcel's "
                       "local gas state is used for the terminal velocity)");
    }
    if (p.has("reference_fluid_density")) {
      reference_density_ = p.positive("reference_fluid_density");
      reference_viscosity_ = p.positive("reference_fluid_viscosity");
      if (!(particle_density_ > reference_density_)) {
        throw ModelError(p.owner() +
                         ": 'particle_density' must exceed "
                         "'reference_fluid_density' (the particle must settle)");
      }
    }
  } else {
    for (const char* key :
         {"particle_density", "reference_fluid_density", "reference_fluid_viscosity"}) {
      if (p.has(key)) {
        throw ModelError(p.owner() + ": parameter '" + key +
                         "' is only used with filtered: "
                         "true; remove it or set filtered: true");
      }
    }
  }
}

std::vector<std::string> BeetstraDrag::requiredFields() const {
  auto f = denseDragFields();
  if (filtered_) f.push_back("cell_size");
  return f;
}

void BeetstraDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  if (!filtered_) {
    const double factor = parcel_factor_ ? std::exp(k_ * (1.0 - c.cg)) : 1.0;
    evaluateDrag(*this, p, c, K,
                 [factor](double eps, double Re) { return factor * eps * beetstraF(eps, Re); });
    return;
  }
  const std::string owner = dragOwner(name());
  validateConstants(owner, c);
  checkInputs(owner, requiredFields(), p, c);
  const double g = std::sqrt(c.gravity[0] * c.gravity[0] + c.gravity[1] * c.gravity[1] +
                             c.gravity[2] * c.gravity[2]);
  if (!(g > 0.0)) {
    throw ModelError(owner +
                     ": filtered: true needs gravity (constants.gravity) to be non-zero: "
                     "the Radl & Sundaresan length scale is built on the settling velocity");
  }
  const double cg3 = c.cg * c.cg * c.cg;
  const double factor = parcel_factor_ ? std::exp(k_ * (1.0 - c.cg)) : 1.0;
  // Terminal velocity once per distinct (d, rho, mu): remember the last one; when the fluid
  // state changes (compressible gas), start Newton from the last Re_t (2-3 iterations).
  double last_d = -1.0, last_rho = -1.0, last_mu = -1.0, L_c = 0.0, last_Re_t = 0.0;
  const bool reference = reference_density_ > 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) {
      K[i] = 0.0;
      continue;
    }
    const ParcelState s = parcelState(p, c, i);
    const double rho_t = reference ? reference_density_ : s.rho;
    const double mu_t = reference ? reference_viscosity_ : s.mu;
    if (s.d != last_d || rho_t != last_rho || mu_t != last_mu) {
      if (!(particle_density_ > rho_t)) {
        throw ModelError(owner + ": particle_density " + std::to_string(particle_density_) +
                         " kg/m3 is not above the fluid density " + std::to_string(rho_t) +
                         " kg/m3 of parcel " + std::to_string(i) +
                         ": the settling velocity of the filtered correction is undefined");
      }
      const double u_t =
          beetstraTerminalVelocity(s.d, particle_density_, rho_t, mu_t, g, last_Re_t);
      last_Re_t = rho_t * s.d * u_t / mu_t;
      L_c = radlSundaresanLength(u_t, g, s.d);
      last_d = s.d;
      last_rho = rho_t;
      last_mu = mu_t;
    }
    const double corr = radlSundaresanCorrection(1.0 - s.eps, L_c, p.cell_size[i]);
    K[i] =
        cg3 * 3.0 * std::numbers::pi * s.mu * s.d * s.eps * beetstraF(s.eps, s.Re) * corr * factor;
  }
  checkOutputs(owner, "drag coefficient K", K, p.n);
}

}  // namespace cosim::models
