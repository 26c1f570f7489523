// The exponential drag update reproduces the exact solution of m dv/dt = K (u_f - v) + F.
#include "cosim/liggghts/exponential_drag.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace cosim::liggghts;

// One explicit step with the effective force gives v = u* + (v0 - u*) exp(-K dt / m),
// u* = u_f + F/K, for mild and extremely stiff relaxation (K dt / m from 1e-3 to 1e3).
TEST(ExponentialDrag, OneStepIsExact) {
  const double m = 2e-6, uf = 0.7, v0 = -1.3, F = -3e-5;
  for (double a : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
    const double dt = 1e-6, K = a * m / dt;
    const double v1 = v0 + dt * exponentialDragForce(K, m, dt, uf, v0, F) / m;
    const double ustar = uf + F / K;
    EXPECT_NEAR(v1, ustar + (v0 - ustar) * std::exp(-a), 1e-12) << "K dt/m = " << a;
  }
}

// Without drag the update is the plain explicit force.
TEST(ExponentialDrag, NoDragIsPlainForce) {
  EXPECT_DOUBLE_EQ(exponentialDragForce(0.0, 1.0, 1e-3, 5.0, 1.0, 2.5), 2.5);
  EXPECT_NEAR(exponentialDragFactor(1e-12), 1.0, 1e-12);
  EXPECT_NEAR(exponentialDragFactor(1e-7), 1.0 - 0.5e-7, 1e-14);
}
