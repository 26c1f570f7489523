#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

// A parcel at rest in still gas: hydrostatic grad p = rho_f g, so the force is the buoyancy and
// weight + force = (rho_p - rho_f) V g.
TEST(PressureGradient, BedAtRestCarriesWeightMinusBuoyancy) {
  auto f = Registry::instance().makeForce("pressure_gradient", Parameters("pressure_gradient"));
  Batch b;
  b.add(0.4, 0.0, kD, 5.0);  // parcel radius 0.75 mm
  const double g = -9.81;
  b.pressure_gradient = {0.0, 0.0, kRho * g};
  std::vector<double> force = {1.0, 2.0, 0.0};  // addForces adds to what is there
  f->addForces(b.view(), constants(5.0), force.data());
  // V = 4/3 pi (7.5e-4)^3 = 1.7671458676442585e-09 m3 (python3)
  const double V = 1.7671458676442585e-09;
  EXPECT_DOUBLE_EQ(force[0], 1.0);
  EXPECT_DOUBLE_EQ(force[1], 2.0);
  EXPECT_TRUE(close(force[2], -V * kRho * g, 1e-13));
  const double weight = kRhoP * V * g;
  EXPECT_TRUE(close(weight + force[2], (kRhoP - kRho) * V * g, 1e-13));
}

TEST(PressureGradient, OpposesTheGradientInEveryDirection) {
  auto f = Registry::instance().makeForce("pressure_gradient", Parameters("pressure_gradient"));
  Batch b;
  b.add(0.5, 0.0, 1e-3, 1.0);  // radius 0.5 mm: V = 5.235987755982989e-10 m3
  b.pressure_gradient = {100.0, -200.0, 50.0};
  std::vector<double> force(3, 0.0);
  f->addForces(b.view(), constants(1.0), force.data());
  const double V = 5.235987755982989e-10;
  EXPECT_TRUE(close(force[0], -100.0 * V, 1e-13));
  EXPECT_TRUE(close(force[1], 200.0 * V, 1e-13));
  EXPECT_TRUE(close(force[2], -50.0 * V, 1e-13));
}

}  // namespace
}  // namespace cosim::models::test
