// The gas solver on a mesh whose faces are not orthogonal to the cell-centre connections: a
// round column of 50 mm as an O-grid (cases/cylinder, cells up to 14 degrees non-orthogonal,
// skewness 0.9), slip walls. A uniform inflow must stay uniform (plug flow is the exact solution)
// with the hydrostatic pressure difference, and a gas at rest must stay at rest. Before the cell
// velocity was reconstructed without fvc::reconstruct (adapters/openfoam/gas/reconstructFaceFlux.H)
// this mesh blew the gas up within a few steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "foam_harness.h"
#include "gas_constants.h"

namespace cosim::test {
namespace {

constexpr double kHeight = 0.08, kCellHeight = 0.005;

// Probes on a 2.5 mm grid inside the column at three heights: every cell holds some
std::vector<double> probeGrid() {
  std::vector<double> xyz;
  for (const double z : {0.0125, 0.0425, 0.0725})
    for (double y = -0.0235; y < 0.0236; y += 0.0025)
      for (double x = -0.0235; x < 0.0236; x += 0.0025)
        if (std::hypot(x, y) < 0.0235) xyz.insert(xyz.end(), {x, y, z});
  return xyz;
}

FoamRunConfig cylinderCase(double inlet_velocity, bool hydrostatic) {
  FoamRunConfig cfg;
  cfg.case_name = "cylinder";
  cfg.substitute = {{"inlet_velocity", std::to_string(inlet_velocity)},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.options_yaml = hydrostatic ? "{hydrostatic_start: true}" : "{hydrostatic_start: false}";
  cfg.send = {"fluid_velocity", "voidage"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  return cfg;
}

// Largest |u - u0 e_z| over the probes
double largestDeviation(const cosim::link::ParticleData& at, double u0) {
  const auto& u = at.get("fluid_velocity");
  double worst = 0;
  for (std::size_t i = 0; i < at.size(); ++i)
    worst = std::max(worst, std::hypot(u[3 * i], u[3 * i + 1], u[3 * i + 2] - u0));
  return worst;
}

TEST(OpenFoamCylinder, UniformInflowStaysUniformOnTheOGrid) {
  const double u0 = 0.2;
  FoamRun run(cylinderCase(u0, true));
  const cosim::link::ParticleData probes = makeParticles(probeGrid(), 1e-5);
  ASSERT_EQ(probes.size(), 822u);
  double worst = 0, drop = 0;
  cosim::wire::Advanced last;
  for (int step = 0; step < 50; ++step) {
    const auto reply = run.sample(probes);
    ASSERT_TRUE(reply.lost.empty());
    worst = std::max(worst, largestDeviation(reply.at, u0));
    last = run.advance(2e-3, cosim::link::ParticleData{});
    drop = last.fluid().pressure_drop();
  }
  worst = std::max(worst, largestDeviation(run.sample(probes).at, u0));
  // Mass through: what enters leaves (the gas column is in equilibrium)
  EXPECT_NEAR(last.fluid().gas_mass_out(), last.fluid().gas_mass_in(),
              1e-6 * last.fluid().gas_mass_in());
  // The zero-gradient inlet face carries the first cell's pressure, half a cell above the inlet
  const double hydrostatic = gas::density(gas::p_out) * gas::g * (kHeight - kCellHeight / 2);
  std::printf(
      "O-grid plug flow at %.2f m/s: largest |u - u0| %.3g m/s over 50 steps, pressure "
      "drop %.5f Pa (hydrostatic %.5f Pa)\n",
      u0, worst, drop, hydrostatic);
  EXPECT_LT(worst, 2e-5 * u0);
  EXPECT_NEAR(drop, hydrostatic, 1e-4 * hydrostatic);
  EXPECT_EQ(run.shutdown(), 0);
}

TEST(OpenFoamCylinder, GasAtRestStaysAtRestOnTheOGrid) {
  FoamRun run(cylinderCase(0, true));
  const cosim::link::ParticleData probes = makeParticles(probeGrid(), 1e-5);
  double worst = 0, drop = 0;
  for (int step = 0; step < 20; ++step) {
    worst = std::max(worst, largestDeviation(run.sample(probes).at, 0));
    drop = run.advance(2e-3, cosim::link::ParticleData{}).fluid().pressure_drop();
  }
  worst = std::max(worst, largestDeviation(run.sample(probes).at, 0));
  const double hydrostatic = gas::density(gas::p_out) * gas::g * (kHeight - kCellHeight / 2);
  std::printf("O-grid gas at rest: largest |u| %.3g m/s over 20 steps, pressure drop %.5f Pa\n",
              worst, drop);
  EXPECT_LT(worst, 5e-8);
  EXPECT_NEAR(drop, hydrostatic, 1e-4 * hydrostatic);
  EXPECT_EQ(run.shutdown(), 0);
}

}  // namespace
}  // namespace cosim::test
