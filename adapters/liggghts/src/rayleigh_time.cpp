#include "cosim/liggghts/rayleigh_time.h"

#include <cmath>
#include <numbers>

namespace cosim::liggghts {

double rayleighTime(double radius, double density, double youngs_modulus, double poisson_ratio) {
  const double shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  return std::numbers::pi * radius * std::sqrt(density / shear_modulus) /
         (0.1631 * poisson_ratio + 0.8766);
}

}  // namespace cosim::liggghts
