// Verification 4b: a bed at its packing limit with gas through it (scenarios/fluidized-bed:
// 1000 parcels of 1.5 mm settled on the distributor, cosimFoam + LIGGGHTS), gas at 0.02 m/s
// (below u_mf = 0.0512 m/s, Wen-Yu for the real 300 um grains), with the voidage bound raised
// to 0.40 so that the settled bed (eps ~ 0.4) sits on it. Must stay stable: the orchestrator's
// runtime checks (NaN/Inf, voidage in (0, 1], particle speed, Courant) pass for every step, the
// bed stays put, and the pressure drop is positive and below the bed weight less buoyancy
// (1000 * pi/6 * (1.5e-3)^3 * (1750 - 1.1231) * 9.81 / 0.016^2 = 118.43 Pa) plus the gas
// column (1.1231 * 9.81 * 0.064 = 0.705 Pa): a fixed bed carries only part of its weight on the gas.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/link/fields.h"
#include "run_scene.h"

using cosim::verification::runScene;
namespace field = cosim::field;

TEST(PackedBed, BedAtTheVoidageBoundStaysStableAndBounded) {
  auto r = runScene("fluidized-bed",
                    {"u0=0.02", "end_time=0.05", "average_after=0.02", "constants.min_voidage=0.4",
                     "participants.fluid.options.min_voidage=0.4"},
                    "packed");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(r.final_state.size(), 1000u);
  const auto& v = r.final_state.get(field::velocity);
  double vmax = 0;
  for (double c : v) {
    ASSERT_TRUE(std::isfinite(c));
    vmax = std::max(vmax, std::fabs(c));
  }
  EXPECT_LT(vmax, 0.05) << "a packed bed below u_mf must not move";
  double dp = NAN;
  for (const auto& o : r.observables) {
    if (o.name == "bed_pressure_drop") dp = o.value;
  }
  std::printf("packed bed: pressure drop %.4g Pa, max grain speed %.3g m/s\n", dp, vmax);
  ASSERT_TRUE(std::isfinite(dp));
  EXPECT_GT(dp, 0.705);
  EXPECT_LT(dp, 118.43 + 0.705);
}
