// Independent numbers the OpenFOAM adapter tests compare against (N2 perfect gas, 300 K).
#pragma once

namespace cosim::test::gas {

inline constexpr double R = 8.314462618;  // J/(mol K)
inline constexpr double M = 0.0280134;    // kg/mol, N2
inline constexpr double T = 300.0;        // K
inline constexpr double mu = 1.8e-5;      // Pa s
inline constexpr double g = 9.81;         // m/s2
inline constexpr double p_out = 1e5;      // Pa
inline double density(double p) { return p * M / (R * T); }

}  // namespace cosim::test::gas
