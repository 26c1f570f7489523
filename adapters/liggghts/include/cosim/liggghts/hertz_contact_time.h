// Duration of an elastic Hertz contact at impact speed v:
//   t_H = 2.87 (m_eff^2 / (r_eff E_eff^2 v))^(1/5)
// with 1/m_eff = 1/m1 + 1/m2, 1/r_eff = 1/r1 + 1/r2, 1/E_eff = (1-nu1^2)/E1 + (1-nu2^2)/E2
// (docs/physics.md section 7).
#pragma once

namespace cosim::liggghts {

double hertzContactTime(double effective_mass, double effective_radius, double effective_modulus,
                        double impact_speed);

// Two identical spheres (the usual particle-particle collision).
double hertzContactTimeIdenticalSpheres(double radius, double density, double youngs_modulus,
                                        double poisson_ratio, double impact_speed);
// A sphere against a rigid flat wall (the shortest contact a particle of this material has).
double hertzContactTimeRigidWall(double radius, double density, double youngs_modulus,
                                 double poisson_ratio, double impact_speed);

}  // namespace cosim::liggghts
