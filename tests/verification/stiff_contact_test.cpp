// Verification 4f: a contact stiffness far too high for the DEM step is refused before the
// run, with the step that would work, by the orchestrator (from the DEM dt / Rayleigh time the
// LIGGGHTS adapter reports from its script's material, the one source of material data; the
// constants agree here) and by the LIGGGHTS adapter itself (dt_check=refuse).
// Scene: verify-terminal-velocity/stokes.yaml (r = 10 um, rho = 1000 kg/m3, DEM dt = 1e-5 s)
// with E = 1e9 Pa (LIGGGHTS' own SI limit), nu = 0.3. Hand value: G = E / (2 (1 + nu)) =
// 3.846e8 Pa, t_R = pi r sqrt(rho / G) / (0.1631 nu + 0.8766) = 5.473e-8 s; dt / t_R = 183;
// dem_steps for dt <= 0.2 t_R: ceil(1e-4 / 1.0947e-8) = 9136. Hertz time at 2 m/s on a wall:
// t_H = 2.87 (m^2 / (r E_eff^2 v))^0.2 = 1.699e-7 s, t_H / 5 = 3.40e-8 s > 0.2 t_R = 1.09e-8 s.
#include <gtest/gtest.h>

#include "run_scene.h"

using cosim::verification::runScene;

TEST(StiffContact, OrchestratorRefusesWithTheDemStepsThatWouldWork) {
  auto r = runScene("verify-terminal-velocity/stokes.yaml",
                    {"E=1e9", "constants.youngs_modulus=1e9", "constants.poisson_ratio=0.3"},
                    "stiff-orch");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.steps, 0u) << "the run must not start";
  EXPECT_NE(r.message.find("Rayleigh"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("dem_steps >= 9136"), std::string::npos) << r.message;
}

TEST(StiffContact, LiggghtsAdapterRefusesWithTheTimestepThatWouldWork) {
  auto r = runScene("verify-terminal-velocity/stokes.yaml",
                    {"E=1e9", "participants.particles.options.dt_check=refuse"}, "stiff-lig");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.steps, 0u) << "the run must not start";
  EXPECT_NE(r.message.find("particles"), std::string::npos) << r.message;
  // the advice is min(0.2 t_R, t_H / 5) = 1.09e-8 s
  EXPECT_NE(r.message.find("1.09"), std::string::npos) << r.message;
}
