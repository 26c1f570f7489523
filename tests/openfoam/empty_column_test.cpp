// Empty column, uniform inflow, slip walls: at steady state the gas mass leaving equals the
// mass entering, and the pressure is hydrostatic: p(inlet face) - p(outlet) = rho g (H - dz/2)
// (the zero-gradient inlet face carries the first cell's pressure, dz/2 above the inlet).
#include <gtest/gtest.h>

#include <cmath>

#include "foam_harness.h"
#include "gas_constants.h"

namespace cosim::test {
namespace {

TEST(OpenFoamEmptyColumn, OutflowEqualsInflowAndPressureIsHydrostatic) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.2"}, {"inlet_precursor", "0"},
                    {"write_steps", "100000"}, {"wall_U", "slip"}};
  cfg.send = {"fluid_velocity", "voidage"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  FoamRun run(cfg);

  const cosim::link::ParticleData none = makeParticles({}, 1e-3);
  cosim::wire::Advanced last;
  for (int step = 0; step < 150; ++step) {
    run.sample(none);
    last = run.advance(2e-3, cosim::link::ParticleData{});
  }
  const auto& s = last.scalars();
  const double in = s.at("gas_mass_in");
  const double out = s.at("gas_mass_out");
  // Inflow: rho * u * A * dt at the inlet
  const double rho_in = gas::density(gas::p_out + 1.08);
  EXPECT_NEAR(in, rho_in * 0.2 * 0.02 * 0.02 * 2e-3, 1e-4 * in);
  EXPECT_NEAR(out, in, 1e-6 * in);

  const double H = 0.1, dz = 0.004;
  const double expected = gas::density(gas::p_out) * gas::g * (H - dz / 2);
  EXPECT_NEAR(s.at("pressure_drop"), expected, 0.005 * expected);
  EXPECT_EQ(run.shutdown(), 0);
}

}  // namespace
}  // namespace cosim::test
