// Empty column, uniform inflow, slip walls: at steady state the gas mass leaving equals the
// mass entering, and the pressure is hydrostatic: p(inlet face) - p(outlet) = rho g (H - dz/2)
// (the zero-gradient inlet face carries the first cell's pressure, dz/2 above the inlet).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>

#include "foam_harness.h"
#include "gas_constants.h"

namespace cosim::test {
namespace {

TEST(OpenFoamEmptyColumn, OutflowEqualsInflowAndPressureIsHydrostatic) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.2"},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.send = {"fluid_velocity", "voidage"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  FoamRun run(cfg);

  const cosim::link::ParticleData none = makeParticles({}, 1e-3);
  cosim::wire::Advanced last;
  for (int step = 0; step < 150; ++step) {
    run.sample(none);
    last = run.advance(2e-3, cosim::link::ParticleData{});
  }
  const auto& s = last.fluid();
  const double in = s.gas_mass_in();
  const double out = s.gas_mass_out();
  // Inflow: rho * u * A * dt at the inlet
  const double rho_in = gas::density(gas::p_out + 1.08);
  EXPECT_NEAR(in, rho_in * 0.2 * 0.02 * 0.02 * 2e-3, 1e-4 * in);
  EXPECT_NEAR(out, in, 1e-6 * in);

  const double H = 0.1, dz = 0.004;
  const double expected = gas::density(gas::p_out) * gas::g * (H - dz / 2);
  EXPECT_NEAR(s.pressure_drop(), expected, 0.005 * expected);
  EXPECT_EQ(run.shutdown(), 0);
}

// The test column (tests/openfoam/cases/column) with slip walls, gas entering at `inflow` [m/s],
// the fluid options `options`.
FoamRunConfig column(const std::string& inflow, const std::string& options) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", inflow},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.options_yaml = options;
  cfg.send = {"fluid_velocity", "voidage"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  return cfg;
}

// Gas at rest (no inflow). Started from a uniform pressure the column falls under gravity and
// rings; with options.hydrostatic_start it starts in equilibrium: the pressure difference is the
// hydrostatic one from the first step and the gas stays at rest.
double restingGasSpeed(bool hydrostatic, double* pressure_drop) {
  FoamRun run(
      column("0", hydrostatic ? "{hydrostatic_start: true}" : "{hydrostatic_start: false}"));
  const cosim::link::ParticleData probe = makeParticles({0.0, 0.0, 0.05}, 1e-5);
  double speed = 0;
  for (int step = 0; step < 5; ++step) {
    const auto reply = run.sample(probe);
    speed = std::max(speed, std::fabs(reply.at.get("fluid_velocity")[2]));
    const auto adv = run.advance(2e-3, cosim::link::ParticleData{});
    if (step == 0) *pressure_drop = adv.fluid().pressure_drop();
  }
  EXPECT_EQ(run.shutdown(), 0);
  return speed;
}

TEST(OpenFoamEmptyColumn, HydrostaticStartKeepsGasAtRest) {
  const double H = 0.1, dz = 0.004;
  const double expected = gas::density(gas::p_out) * gas::g * (H - dz / 2);
  double dp_uniform = 0, dp_hydro = 0;
  const double ringing = restingGasSpeed(false, &dp_uniform);
  const double resting = restingGasSpeed(true, &dp_hydro);
  std::printf(
      "resting gas: largest |u_z| %.3g m/s from a uniform start, %.3g m/s from a hydrostatic one\n",
      ringing, resting);
  // uniform start: the column settles into its pressure gradient with a velocity of ~0.2 mm/s
  EXPECT_GT(ringing, 1e-4);
  // hydrostatic start: rest to far below a Stokes settling speed, equilibrium from step 1
  EXPECT_LT(resting, 1e-5);
  EXPECT_NEAR(dp_hydro, expected, 0.005 * expected);
}

// options.solver_log_every: the linear solvers' residual lines of every N-th gas step only, the
// gas itself unchanged. 20 steps with N = 5: the p solver's lines appear in steps 5, 10, 15 and
// 20 only, a fifth of those with N = 1, and the pressure drop after the 20 steps is the same to
// the bit.
std::pair<int, double> residualLines(const std::string& options) {
  FoamRun run(column("0.2", options));
  const cosim::link::ParticleData probe = makeParticles({0.0, 0.0, 0.05}, 1e-5);
  double dp = 0;
  for (int step = 0; step < 20; ++step) {
    run.sample(probe);
    dp = run.advance(2e-3, cosim::link::ParticleData{}).fluid().pressure_drop();
  }
  EXPECT_EQ(run.shutdown(), 0);
  std::ifstream log(run.caseDir() + "/log.cosimFoam");
  std::string line;
  int n = 0;
  while (std::getline(log, line)) n += line.find("Solving for p,") != std::string::npos;
  return {n, dp};
}

TEST(OpenFoamEmptyColumn, SolverResidualsAreLoggedEveryNthStepOnly) {
  const auto every = residualLines("{}");
  const auto fifth = residualLines("{solver_log_every: 5}");
  EXPECT_GT(every.first, 0);
  EXPECT_EQ(every.first % 20, 0) << "the same number of p solves in each step";
  EXPECT_EQ(fifth.first * 5, every.first);
  EXPECT_EQ(fifth.second, every.second) << "logging changed the gas";
}

}  // namespace
}  // namespace cosim::test
