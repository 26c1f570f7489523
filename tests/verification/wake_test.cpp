// Verification 4 (docs/verification.md): the particle's own disturbance of the gas it samples
// (models.drag.undisturbed_velocity). One 20 um sphere (rho_p 1000, Stokes drag, no buoyancy
// force), two-way coupled with the REAL solvers (cosimFoam + LIGGGHTS) in cells of 2, 3 and 5
// particle diameters, centred in its cell (scenarios/verify-wake). The gas flows up at the
// terminal slip and the sphere starts at rest, so with the right drag it stays where it is.
// Reference, closed form: w_t = rho_p g d^2 / (18 mu) = 1000 * 9.81 * (20e-6)^2 / (18 * 1.8e-5)
// = 1.211111111e-2 m/s (Re 0.015, tau_p = 1.2346e-3 s). Each test runs the scene three times,
// to 20 ms (16 tau_p), and compares the slip u_up - v_p at the end with w_t:
//   none                         as sampled (asserted to be far off: what the others correct)
//   self_disturbance             the steady estimate
//   self_disturbance_transient   the estimate built up in time (wake_buildup.h)
// These three use the lattice estimate (self_disturbance_gain 1, _offset 0); the scenes carry
// their calibration for cosimFoam, which CalibratedSphereKeepsItsTerminalVelocity checks over
// 0.1 s. Tolerances: 1.5-3 x what each reaches (docs/verification.md section 4 has the tables).
// About 60-70 s per test on a loaded 2-core machine (three runs of 23^3 cells).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cosim/link/fields.h"
#include "run_scene.h"

using cosim::verification::runScene;
namespace field = cosim::field;

namespace {

constexpr double kWt = 1.211111111e-2;

double slip(const char* scene, const std::vector<std::string>& sets, const std::string& tag) {
  auto r = runScene(scene, sets, tag);
  EXPECT_EQ(r.exit_code, 0) << r.message;
  if (r.exit_code != 0 || r.final_state.size() != 1) return NAN;
  return kWt - r.final_state.get(field::velocity)[2];  // u_up = w_t
}

struct Errors {
  double none, steady, transient;  // relative error of the slip
};

Errors errors(const char* scene, const char* tag) {
  auto with = [&](const char* choice) {
    return slip(scene,
                {std::string("models.drag.undisturbed_velocity=") + choice, "gain=1", "offset=0"},
                std::string(tag) + "-" + choice) /
               kWt -
           1.0;
  };
  const Errors e{with("none"), with("self_disturbance"), with("self_disturbance_transient")};
  std::printf(
      "%s: terminal slip error without correction %+.2f %%, steady %+.3f %%, built up in time "
      "%+.3f %%\n",
      tag, 100 * e.none, 100 * e.steady, 100 * e.transient);
  EXPECT_GT(e.none, 0.2) << "the uncorrected drag must show the sphere's own wake";
  return e;
}

}  // namespace

TEST(Wake, SphereInCellsOfTwoDiameters) {
  const Errors e = errors("verify-wake/scenario.yaml", "cells-2d");
  // steady: -3.05 %, it over-corrects while the wake builds up (the sphere is pushed up)
  EXPECT_NEAR(e.steady, 0.0, 0.046);
  // built up in time: +0.17 % (the 0.5 % requirement is met)
  EXPECT_NEAR(e.transient, 0.0, 0.005);
}

TEST(Wake, SphereInCellsOfThreeDiameters) {
  const Errors e = errors("verify-wake/cells3.yaml", "cells-3d");
  EXPECT_NEAR(e.steady, 0.0, 0.007);      // -0.46 %
  EXPECT_NEAR(e.transient, 0.0, 0.0065);  // +0.45 % (met, by a small margin)
}

TEST(Wake, SphereInCellsOfFiveDiameters) {
  const Errors e = errors("verify-wake/cells5.yaml", "cells-5d");
  EXPECT_NEAR(e.steady, 0.0, 0.014);     // -0.95 %
  EXPECT_NEAR(e.transient, 0.0, 0.004);  // -0.15 % (met)
}

// The scenes as shipped: the estimate built up in time and calibrated for cosimFoam with each
// scene's mesh, sphere, solver settings and time step (gain, offset: two held-sphere runs and
// held_forms.py, docs/models.md "Calibrating for the gas solver"). Calibrated on a sphere held
// still to 1 s; checked here on the free sphere, which starts at rest, must build its wake up and
// keep its terminal slip. 0.1 s (81 tau_p, 500 steps) per scene: by then the lattice estimate has
// crept to +1.2 % in cells of 2 diameters (section 4); reached: +0.15 / +0.21 / +0.19 %.
TEST(Wake, CalibratedSphereKeepsItsTerminalVelocity) {
  int n = 0;
  for (const char* scene :
       {"verify-wake/scenario.yaml", "verify-wake/cells3.yaml", "verify-wake/cells5.yaml"}) {
    const double e =
        slip(scene, {"end_time=0.1"}, std::string("calibrated-") + std::to_string(n++)) / kWt - 1.0;
    std::printf("%s, calibrated, 0.1 s: terminal slip error %+.3f %%\n", scene, 100 * e);
    EXPECT_NEAR(e, 0.0, 0.005) << scene;  // the 0.5 % the issue asks for
  }
}

// The wake history is the coupler's state: the checkpoint holds it (per parcel id, with the
// interval not yet taken into it), and a checkpoint without it is not resumed.
TEST(Wake, TransientHistoryIsCheckpointedAndNotResumedWithoutIt) {
  namespace fs = std::filesystem;
  const std::vector<std::string> sets = {
      "models.drag.undisturbed_velocity=self_disturbance_transient", "coupling.end_time=0.002",
      "checkpoint.interval=0.002"};
  auto r = runScene("verify-wake/scenario.yaml", sets, "cells-2d-checkpoint");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  const fs::path run =
      fs::temp_directory_path() / ("cosim-verify-cells-2d-checkpoint-" + std::to_string(getpid()));
  const fs::path state = run / "checkpoints/0.002/orchestrator.json";
  ASSERT_TRUE(fs::exists(state));
  nlohmann::json j;
  std::ifstream(state) >> j;
  ASSERT_TRUE(j.contains("wake"));
  const auto& parcels = j.at("wake").at("parcels");
  ASSERT_EQ(parcels.size(), 1u);
  EXPECT_EQ(parcels[0].at(0).get<std::int64_t>(), r.final_state.ids.at(0));
  EXPECT_EQ(parcels[0].at(5).get<double>(), 2.0e-4);     // the last interval, not yet in the modes
  EXPECT_GT(parcels[0].at(2).at(2).get<double>(), 0.0);  // the fastest mode has built up (z)

  j.erase("wake");
  std::ofstream(state) << j.dump();
  cosim::orchestrator::RunOptions o;
  o.quiet = true;
  o.resume = run;
  auto sets_longer = sets;
  sets_longer.push_back("coupling.end_time=0.004");
  const auto resumed =
      cosim::orchestrator::Coupler(
          cosim::orchestrator::loadScenario(
              fs::path(COSIM_SOURCE_DIR) / "scenarios/verify-wake/scenario.yaml", sets_longer),
          o)
          .run();
  EXPECT_NE(resumed.exit_code, 0);
  EXPECT_NE(resumed.message.find("no wake history"), std::string::npos) << resumed.message;
  EXPECT_NE(resumed.message.find("self_disturbance_transient"), std::string::npos);
  fs::remove_all(run);
}
