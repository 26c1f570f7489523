// Verification 2: fluidization curve with the real solvers (scenarios/fluidized-bed, 1000
// parcels of 1.5 mm = cg 5 x 300 um MCC, 16 x 16 mm column, Beetstra drag + pressure gradient).
// Pressure drop (inlet - outlet patch average, averaged over 0.1-0.2 s) against the superficial
// velocity: linear below minimum fluidization (Darcy regime, particle Re 0.4-0.75), flat at
// bed weight less buoyancy over the area above it.
// Hand values: bed weight less buoyancy / area = 1000 * pi/6 * (1.5e-3)^3 * (1750 - 1.1231)
//   * 9.81 / 0.016^2 = 118.43 Pa; gas column 1.1231 * 9.81 * 0.064 = 0.705 Pa; total 119.135 Pa.
// Wen & Yu (1966) for the real grains: Ar = rho_g (rho_p - rho_g) g d^3 / mu^2 = 1605.7,
//   Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7 = 0.9584, u_mf = Re_mf mu / (rho_g d) = 0.0512 m/s.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bed_resistance.h"
#include "run_scene.h"

using cosim::verification::runScene;

namespace {
std::vector<double> g_fixed_bed_voidage;  // cell voidages of the slowest run (the fixed bed)

double pressureDrop(double u0) {
  const std::string u = std::to_string(u0);
  auto r = runScene("fluidized-bed", {"u0=" + u, "end_time=0.2", "average_after=0.1"},
                    "fluidization-" + u);
  EXPECT_EQ(r.exit_code, 0) << r.message;
  if (g_fixed_bed_voidage.empty() && r.exit_code == 0) {
    g_fixed_bed_voidage = cosim::verification::readFoamScalarField(
        cosim::verification::latestTime(r.folder / "fluid") / "voidage", 4 * 4 * 16);
  }
  for (const auto& o : r.observables) {
    if (o.name == "bed_pressure_drop") return o.value;
  }
  return NAN;
}
}  // namespace

TEST(FluidizationCurve, RisesLinearlyThenFlatAtBedWeight) {
  constexpr double kPlateau = 118.43 + 0.705;  // Pa
  constexpr double kWenYu = 0.0512;            // m/s
  const double dp1 = pressureDrop(0.02), dp2 = pressureDrop(0.04), dp3 = pressureDrop(0.15);
  std::printf(
      "fluidization curve: dp(0.02) = %.4g Pa, dp(0.04) = %.4g Pa, dp(0.15) = %.4g Pa (plateau "
      "%.4g)\n",
      dp1, dp2, dp3, kPlateau);
  // fixed bed: pressure drop proportional to the velocity (Darcy; the inertial Ergun term is a
  // few % at particle Re 0.75)
  EXPECT_NEAR(dp2 / dp1, 2.0, 0.05);  // reached 1.981
  EXPECT_LT(dp2, kPlateau);
  // fluidized: the gas carries the bed
  EXPECT_NEAR(dp3, kPlateau, 0.03 * kPlateau);  // reached -1.1 %
  // minimum fluidization: the fixed-bed line through the origin meets the plateau
  const double slope = (dp1 / 0.02 + dp2 / 0.04) / 2;
  const double u_mf = kPlateau / slope;
  std::printf("u_mf from the curve %.4g m/s, Wen-Yu %.4g m/s (ratio %.3g)\n", u_mf, kWenYu,
              u_mf / kWenYu);
  EXPECT_GT(u_mf, 0.04);  // above the fixed-bed points
  EXPECT_LT(u_mf, 0.15);  // below the fluidized point
  // Independent: the superficial velocity at which Beetstra's law on the fixed bed's own cell
  // voidages (bed_resistance.h) carries the bed weight less buoyancy.
  ASSERT_EQ(g_fixed_bed_voidage.size(), 256u);
  const cosim::verification::Gas gas{1.123079, 1.8e-5};
  auto bedDrop = [&](double u) {
    return cosim::verification::bedPressureDrop(g_fixed_bed_voidage, 16, 0.004, u, 300e-6, gas,
                                                cosim::verification::beetstraDimensionless);
  };
  double lo = 0.001, hi = 1.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (bedDrop(mid) < 118.43 ? lo : hi) = mid;
  }
  const double u_mf_law = 0.5 * (lo + hi);
  std::printf("u_mf from Beetstra on the fixed bed's cell voidages %.4g m/s; curve/law %.4f\n",
              u_mf_law, u_mf / u_mf_law);
  EXPECT_NEAR(u_mf / u_mf_law, 1.0, 0.03);
}
