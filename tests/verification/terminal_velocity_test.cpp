// Verification 1: one sphere two-way coupled with the REAL solvers (cosimFoam gas, LIGGGHTS
// particle) reaches its analytic terminal slip. The gas flows up a slip-walled column at
// u_up = w_t and the sphere is launched with the gas; the slip u_up - v_p must reach w_t.
// References (tests/verification/reference.py): N2 at 1e5 Pa, 300 K, rho_f = 1.123079 kg/m3,
// mu = 1.8e-5 Pa s.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/link/fields.h"
#include "run_scene.h"

using cosim::verification::runScene;
namespace field = cosim::field;

namespace {

struct Case {
  const char* scene;
  const char* tag;
  double w_t;            // analytic terminal slip [m/s]
  double w_at_end;       // slip of the exact transient (ODE) at end_time [m/s]
  double tol_terminal;   // relative tolerance against w_t (the requirement is 1 %)
  double tol_transient;  // relative tolerance against w_at_end
};

double finalSlip(const Case& c) {
  auto r = runScene(c.scene, {}, c.tag);
  EXPECT_EQ(r.exit_code, 0) << r.message;
  if (r.exit_code != 0 || r.final_state.size() != 1) return NAN;
  const double vz = r.final_state.get(field::velocity)[2];
  const double slip = c.w_t - vz;  // u_up = w_t in the scene
  std::printf("%s: slip %.9e m/s, analytic terminal %.9e (%+.3e), transient at end %.9e (%+.3e)\n",
              c.tag, slip, c.w_t, slip / c.w_t - 1, c.w_at_end, slip / c.w_at_end - 1);
  return slip;
}

// Both checks; the tolerances are 3-5 times what is reached (docs/verification.md).
void expectSlip(const Case& c) {
  const double slip = finalSlip(c);
  EXPECT_NEAR(slip, c.w_t, c.tol_terminal * c.w_t);
  EXPECT_NEAR(slip, c.w_at_end, c.tol_transient * c.w_at_end);
}

}  // namespace

// Stokes: v_t = (rho_p - rho_f) g d^2 / (18 mu) = (1000 - 1.123079) * 9.81 * (20e-6)^2 /
// (18 * 1.8e-5) = 1.209750937e-2 m/s; tau = 1000 * 4e-10 / 3.24e-4 = 1.2345679e-3 s; at the
// end time 10 ms the exact transient has slip v_t (1 - exp(-8.1)) = 1.209383731e-2 m/s.
// Reached: -3.0e-4 from v_t (the transient is not quite finished), +4.3e-6 from the transient.
TEST(TerminalVelocity, StokesRegimeWithRealSolvers) {
  expectSlip({"verify-terminal-velocity/stokes.yaml", "stokes", 1.209750937e-2, 1.209383731e-2,
              1e-3, 2e-5});
}

// Schiller-Naumann, d = 180 um, rho_p = 1500: w_t = 0.8589709185 m/s (Re_t = 9.65), transient
// slip at the scene's end time 0.5 s = 0.8582695033 m/s (RK4 of m dw/dt = (m - m_f) g - 3 pi mu
// d w f(Re) to 0.5 s).
// Reached: -5.4e-4 from w_t, +2.8e-4 from the transient.
TEST(TerminalVelocity, SchillerNaumannRe10WithRealSolvers) {
  expectSlip(
      {"verify-terminal-velocity/scenario.yaml", "re10", 0.8589709185, 0.8582695033, 2e-3, 1e-3});
}

// Schiller-Naumann, d = 600 um, rho_p = 1200: w_t = 2.800589452 m/s (Re_t = 104.8), transient
// slip at 1.2 s = 2.794184842 m/s.
// Reached: -1.5e-3 from w_t (the transient is not finished at 1.2 s), +7.9e-4 from the transient.
TEST(TerminalVelocity, SchillerNaumannRe100WithRealSolvers) {
  expectSlip(
      {"verify-terminal-velocity/re100.yaml", "re100", 2.800589452, 2.794184842, 5e-3, 3e-3});
}
