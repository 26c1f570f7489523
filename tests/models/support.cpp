#include "support.h"

namespace cosim::models::test {

void Batch::add(double eps, double slip, double d_real, double cg, double rho, double mu,
                double cell) {
  const std::size_t i = radius.size();
  position.insert(position.end(), {0.001 * static_cast<double>(i), 0.0, 0.0});
  velocity.insert(velocity.end(), {0.1, -0.2, 0.3});
  fluid_velocity.insert(fluid_velocity.end(), {0.1 + 0.6 * slip, -0.2, 0.3 + 0.8 * slip});
  radius.push_back(cg * d_real / 2.0);
  voidage.push_back(eps);
  fluid_density.push_back(rho);
  fluid_viscosity.push_back(mu);
  pressure_gradient.insert(pressure_gradient.end(), {0.0, 0.0, 0.0});
  precursor_fraction.push_back(0.011);
  cell_size.push_back(cell);
}

SceneConstants constants(double cg, double min_voidage) {
  SceneConstants c;
  c.cg = cg;
  c.min_voidage = min_voidage;
  return c;
}

}  // namespace cosim::models::test
