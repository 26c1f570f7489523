// Rayleigh time of a sphere: the time a Rayleigh surface wave needs to cross half the sphere.
//   t_R = pi r sqrt(rho_p / G) / (0.1631 nu + 0.8766),   G = E / (2 (1 + nu))
// DEM time steps are normally 10-20 % of t_R (docs/physics.md section 7).
#pragma once

namespace cosim::liggghts {

// radius [m], density [kg/m3], Young's modulus [Pa], Poisson's ratio [-] -> t_R [s]
double rayleighTime(double radius, double density, double youngs_modulus, double poisson_ratio);

}  // namespace cosim::liggghts
