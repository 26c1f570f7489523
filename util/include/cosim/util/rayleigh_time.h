// Rayleigh time of a sphere: the time a Rayleigh surface wave needs to cross half the sphere.
//   t_R = pi r sqrt(rho_p / G) / (0.1631 nu + 0.8766),   G = E / (2 (1 + nu))
// DEM time steps are normally 10-20 % of t_R (docs/physics.md section 7). The one
// implementation: the orchestrator's check before the run and the LIGGGHTS adapter's time-step
// check both use it, with the same limits.
#pragma once

namespace cosim::util {

// radius [m], density [kg/m3], Young's modulus [Pa], Poisson's ratio [-] -> t_R [s]
double rayleighTime(double radius, double density, double youngs_modulus, double poisson_ratio);

// DEM dt / t_R above this: unstable contacts, refused.
inline constexpr double kRefuseRayleighFraction = 0.3;
// DEM dt / t_R above this: a warning; also the fraction a refusal suggests.
inline constexpr double kWarnRayleighFraction = 0.2;

}  // namespace cosim::util
