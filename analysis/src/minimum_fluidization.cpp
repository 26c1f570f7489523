// Wen-Yu minimum fluidization velocity (minimum_fluidization.h).
#include "cosim/analysis/minimum_fluidization.h"

#include <cmath>
#include <limits>

namespace cosim::analysis {

double wenYuMinimumFluidization(double d, double rho_p, double rho_g, double mu, double g) {
  if (!(d > 0 && rho_p > rho_g && rho_g > 0 && mu > 0 && g > 0)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double ar = d * d * d * rho_g * (rho_p - rho_g) * g / (mu * mu);
  const double re = std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7;
  return re * mu / (rho_g * d);
}

double idealGasDensity(double pressure, double molar_mass, double temperature) {
  constexpr double kGasConstant = 8.314462618;  // [J/(mol K)]
  return pressure * molar_mass / (kGasConstant * temperature);
}

}  // namespace cosim::analysis
