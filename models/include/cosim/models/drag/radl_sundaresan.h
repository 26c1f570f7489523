// Radl & Sundaresan (2014), Chem. Eng. Sci. 117:416-425: filtered-drag correction for coarse
// Euler-Lagrange meshes, coefficients as tabulated in docs/physics.md section 2.
//   corr(phi, Delta) = 1 - h(phi) / (a(phi) L_c / Delta + 1)   (-> 1 as Delta -> 0)
//   L_c = (u_t^2 / g) Fr_p^(-2/3),  Fr_p = u_t^2 / (g d)
//   u_t: terminal velocity of one real particle, from (rho_p - rho) g d^2 / (18 mu) = u_t F(1,
//   Re_t)
//        with Beetstra's F (solved for Re_t: Ar / 18 = Re_t F(1, Re_t), Ar = rho (rho_p - rho) g
//        d^3 / mu^2)
#pragma once

namespace cosim::models {

double radlSundaresanA(double phi);
double radlSundaresanH(double phi);
// Terminal velocity [m/s] of a sphere of diameter d and density rho_p in a fluid (rho, mu),
// gravity magnitude g, drag F(1, Re) of Beetstra. Requires rho_p > rho, g > 0.
double beetstraTerminalVelocity(double d, double rho_p, double rho, double mu, double g);
// Same, Newton started from `guess_Re` (a Reynolds number near the answer, e.g. the previous
// parcel's Re_t = rho d u_t / mu); any guess gives the same converged answer.
double beetstraTerminalVelocity(double d, double rho_p, double rho, double mu, double g,
                                double guess_Re);
// L_c [m] from u_t, g, d.
double radlSundaresanLength(double u_t, double g, double d);
double radlSundaresanCorrection(double phi, double L_c, double Delta);

}  // namespace cosim::models
