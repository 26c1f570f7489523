#include "cosim/liggghts/hertz_contact_time.h"

#include <cmath>
#include <numbers>

namespace cosim::liggghts {

double hertzContactTime(double effective_mass, double effective_radius, double effective_modulus,
                        double impact_speed) {
  return 2.87 *
         std::pow(effective_mass * effective_mass /
                      (effective_radius * effective_modulus * effective_modulus * impact_speed),
                  0.2);
}

namespace {
double sphereMass(double radius, double density) {
  return density * 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}
}  // namespace

double hertzContactTimeIdenticalSpheres(double radius, double density, double youngs_modulus,
                                        double poisson_ratio, double impact_speed) {
  const double m = sphereMass(radius, density);
  const double e_eff = youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
  return hertzContactTime(0.5 * m, 0.5 * radius, e_eff, impact_speed);
}

double hertzContactTimeRigidWall(double radius, double density, double youngs_modulus,
                                 double poisson_ratio, double impact_speed) {
  const double m = sphereMass(radius, density);
  const double e_eff = youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
  return hertzContactTime(m, radius, e_eff, impact_speed);
}

}  // namespace cosim::liggghts
