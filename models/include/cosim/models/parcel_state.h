// The per-parcel quantities every law is built from, computed in ONE place so that all laws
// agree on them:
//   d_real = 2 r / cg                       real (primary) particle diameter [m]
//   eps    = clamp(voidage, min_voidage, 1)  (clampVoidage, the only place voidage is bounded)
//   w      = |u_f - v|                       slip speed [m/s]
//   Re     = rho eps d_real w / mu           particle Reynolds number on the superficial slip
// Header-only so that out-of-tree plugins use the same definitions without linking anything.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "cosim/models/parcels.h"

namespace cosim::models {

// Voidage as every law sees it: bounded to [min_voidage, 1].
inline double clampVoidage(double voidage, const SceneConstants& c) {
  return std::clamp(voidage, c.min_voidage, 1.0);
}

inline double realDiameter(double parcel_radius, const SceneConstants& c) {
  return 2.0 * parcel_radius / c.cg;
}

inline double slipSpeed(const double* fluid_velocity, const double* velocity) {
  const double dx = fluid_velocity[0] - velocity[0];
  const double dy = fluid_velocity[1] - velocity[1];
  const double dz = fluid_velocity[2] - velocity[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

inline double reynolds(double rho, double eps, double d, double w, double mu) {
  return rho * eps * d * w / mu;
}

struct ParcelState {
  double d;    // real particle diameter [m]
  double eps;  // clamped voidage [-]
  double Re;   // Reynolds number [-]
  double mu;   // dynamic viscosity [Pa s]
  double rho;  // fluid density [kg/m3]
};

// Needs radius, velocity, fluid_velocity, voidage, fluid_density, fluid_viscosity.
inline ParcelState parcelState(const ParcelBatch& p, const SceneConstants& c, std::size_t i) {
  ParcelState s;
  s.d = realDiameter(p.radius[i], c);
  s.eps = clampVoidage(p.voidage[i], c);
  s.mu = p.fluid_viscosity[i];
  s.rho = p.fluid_density[i];
  s.Re = reynolds(s.rho, s.eps, s.d, slipSpeed(p.fluid_velocity + 3 * i, p.velocity + 3 * i), s.mu);
  return s;
}

}  // namespace cosim::models
