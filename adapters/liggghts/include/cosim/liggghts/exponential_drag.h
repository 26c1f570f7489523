// Exact exponential integration of linear drag over one DEM step.
//
// Over a step dt the particle obeys m dv/dt = K (u_f - v) + F, with F = every other force on it
// (contacts, gravity, walls, explicit fluid forces) held constant over the step. The exact
// solution relaxes v towards u* = u_f + F/K:
//     v(dt) = u* + (v0 - u*) exp(-K dt / m)
// The equivalent constant force that an explicit update v += dt F_eff / m must apply is
//     F_eff = phi(a) (K (u_f - v0) + F),   a = K dt / m,   phi(a) = (1 - exp(-a)) / a
// phi -> 1 for a -> 0 (plain explicit drag), phi -> 1/a for a >> 1 (velocity set to u* in one
// step, never overshooting): unconditionally stable for any relaxation time m/K, even one
// shorter than the DEM step.
#pragma once

#include <cmath>

namespace cosim::liggghts {

// phi(a) = (1 - exp(-a)) / a, accurate for small a.
inline double exponentialDragFactor(double a) {
  if (a < 1e-8) return 1.0 - 0.5 * a;
  return -std::expm1(-a) / a;
}

// One component of F_eff. K [kg/s], m [kg], dt [s], u_f and v [m/s], other_force [N].
inline double exponentialDragForce(double K, double mass, double dt, double u_f, double v,
                                   double other_force) {
  return exponentialDragFactor(K * dt / mass) * (K * (u_f - v) + other_force);
}

}  // namespace cosim::liggghts
