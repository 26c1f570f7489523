// Test helpers: a batch of parcels built from (voidage, slip speed, real diameter, cg).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "cosim/models/parcels.h"

namespace cosim::models::test {

// The paper's gas and particles (docs/physics.md section 6).
inline constexpr double kMu = 1.8e-5;    // Pa s
inline constexpr double kRho = 1.12;     // kg/m3
inline constexpr double kD = 300e-6;     // m, real diameter
inline constexpr double kRhoP = 1750.0;  // kg/m3

struct Batch : ParcelArrays {
  // Slip of magnitude `slip` along (0.6, 0, 0.8) (a non-axis direction; 0.6^2 + 0.8^2 = 1).
  void add(double eps, double slip, double d_real, double cg, double rho = kRho, double mu = kMu,
           double cell = 4e-3);
};

SceneConstants constants(double cg, double min_voidage = 0.35);

// |a - b| <= rel * |b|
inline bool close(double a, double b, double rel) { return std::abs(a - b) <= rel * std::abs(b); }

}  // namespace cosim::models::test
