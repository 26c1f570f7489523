// Verification 4a: particles whose relaxation time is 100x shorter than the coupling interval,
// real solvers (cosimFoam + LIGGGHTS), scenes verify-terminal-velocity/stokes.yaml with
// d = 1.8 um, coupling interval 1e-3 s, DEM step 1e-4 s:
//   tau = rho_p d^2 / (18 mu) = 1000 * 3.24e-12 / 3.24e-4 = 1.0e-5 s  (interval = 100 tau,
//   DEM step = 10 tau); v_t = (1000 - 1.123079) * 9.81 * 3.24e-12 / 3.24e-4 = 9.79898e-5 m/s.
// Must stay stable and reach v_t.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/link/fields.h"
#include "run_scene.h"

using cosim::verification::runScene;
namespace field = cosim::field;

TEST(StiffDrag, RelaxationTime100xShorterThanCouplingIntervalReachesTerminalVelocity) {
  const double v_t = 9.79898e-5;
  auto r = runScene("verify-terminal-velocity/stokes.yaml",
                    {"d=1.8e-6", "w_t=9.79898e-5", "cfd_dt=1e-3", "end_time=0.02"}, "stiff-drag");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  ASSERT_EQ(r.final_state.size(), 1u);
  const double vz = r.final_state.get(field::velocity)[2];
  ASSERT_TRUE(std::isfinite(vz));
  const double slip = v_t - vz;  // gas at u_up = v_t
  std::printf("stiff drag: slip %.6e m/s against v_t %.6e (%+.2e)\n", slip, v_t, slip / v_t - 1);
  EXPECT_NEAR(slip, v_t, 0.01 * v_t);
  // the sphere hovers: it moved less than 1 um from its launch height 0.05 m
  EXPECT_NEAR(r.final_state.get(field::position)[2], 0.05, 1e-6);
}
