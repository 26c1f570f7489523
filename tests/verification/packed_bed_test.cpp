// Verification 4b: a bed at its packing limit with gas through it (scenarios/fluidized-bed:
// 1000 parcels of 1.5 mm settled on the distributor, cosimFoam + LIGGGHTS), gas at 0.02 m/s
// (below u_mf = 0.0512 m/s, Wen-Yu for the real 300 um grains), with the voidage bound raised
// to 0.40 so that the settled bed (eps ~ 0.4) sits on it. Must stay stable: the orchestrator's
// runtime checks (NaN/Inf, voidage in (0, 1], particle speed, Courant) pass for every step, the
// bed stays put, and the pressure drop is positive and below the bed weight less buoyancy
// (1000 * pi/6 * (1.5e-3)^3 * (1750 - 1.1231) * 9.81 / 0.016^2 = 118.43 Pa) plus the gas
// column (1.1231 * 9.81 * 0.064 = 0.705 Pa): a fixed bed carries only part of its weight on the
// gas.
#include <gtest/gtest.h>

#include <cmath>

#include "bed_resistance.h"
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

// Verification 1 of the physics review (the cell at the distributor): a resting bed's pressure
// drop must be the drag law integrated over the bed, including the half cell between the plate
// and the first cell centre. Reference: bed_resistance.h evaluates the scene's drag law on the
// voidage cosimFoam wrote for each cell at the end (the profile the gas saw; the bed is at rest,
// so it is the same over the averaging window), layer by layer with the layer's cells in
// parallel, plus the gas column rho g H = 1.1231 * 9.81 * 0.064 = 0.705 Pa.
namespace {
void expectBedDropMatchesLaw(const char* law, const std::function<double(double, double)>& f,
                             double tolerance) {
  namespace fs = std::filesystem;
  using namespace cosim::verification;
  constexpr double u0 = 0.02, d = 300e-6, cell = 0.004;
  constexpr Gas gas{1.123079, 1.8e-5};
  auto r = runScene(
      "fluidized-bed",
      {"u0=0.02", "end_time=0.05", "average_after=0.02", std::string("models.drag.law=") + law},
      std::string("packed-") + law);
  ASSERT_EQ(r.exit_code, 0) << r.message;
  double dp = NAN;
  for (const auto& o : r.observables) {
    if (o.name == "bed_pressure_drop") dp = o.value;
  }
  const fs::path last = latestTime(r.folder / "fluid");
  const auto eps = readFoamScalarField(last / "voidage", 4 * 4 * 16);
  const double ref = bedPressureDrop(eps, 16, cell, u0, d, gas, f) + gas.rho * 9.81 * 0.064;
  std::printf(
      "packed bed (%s): pressure drop %.5g Pa, drag law over the cell voidages (%s) %.5g Pa: %+.3f "
      "%%\n",
      law, dp, last.filename().c_str(), ref, 100 * (dp / ref - 1));
  EXPECT_NEAR(dp / ref, 1.0, tolerance);
}
}  // namespace

TEST(PackedBed, PressureDropIsBeetstraOverTheCellVoidages) {
  expectBedDropMatchesLaw("beetstra", cosim::verification::beetstraDimensionless, 0.02);
}

TEST(PackedBed, PressureDropIsErgunOverTheCellVoidages) {
  expectBedDropMatchesLaw("gidaspow", cosim::verification::ergunWenYuDimensionless, 0.02);
}
