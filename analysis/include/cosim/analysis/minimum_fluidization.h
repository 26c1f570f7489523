// Minimum fluidization velocity by the Wen-Yu correlation (Wen & Yu 1966), for a report that
// shows u / u_mf when the scene does not give u_mf:
//   Ar = d^3 rho_g (rho_p - rho_g) g / mu^2,  Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7,
//   u_mf = Re_mf mu / (rho_g d).
// For the real 300 um MCC grains in N2 at 300 K and 1 bar: 0.0512 m/s (docs/physics.md).
#pragma once

namespace cosim::analysis {

// d: grain diameter [m]; rho_p, rho_g: grain and gas density [kg/m3]; mu: gas viscosity [Pa s];
// g: gravity [m/s2]. NaN when an input is not positive.
double wenYuMinimumFluidization(double d, double rho_p, double rho_g, double mu, double g = 9.81);

// Density of an ideal gas [kg/m3]: p M / (R T).
double idealGasDensity(double pressure, double molar_mass, double temperature);

}  // namespace cosim::analysis
