#include "cosim/util/rayleigh_time.h"

#include <cmath>

namespace cosim::util {

double rayleighTime(double radius, double density, double youngs_modulus, double poisson_ratio) {
  constexpr double kPi = 3.14159265358979323846;  // C++17: no std::numbers
  const double shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  return kPi * radius * std::sqrt(density / shear_modulus) / (0.1631 * poisson_ratio + 0.8766);
}

}  // namespace cosim::util
