// The LIGGGHTS side of the adapter in-process (one MPI rank, no sockets): rebound on a wall,
// drag relaxation to the terminal velocity, coating mass by id and through a restart, errors.
#include "cosim/liggghts/engine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include "cosim/liggghts/liggghts_error.h"
#include "test_dir.h"

using namespace cosim::liggghts;
using cosim::liggghts::test::dataDir;
using cosim::liggghts::test::ScratchDir;

namespace {

// The single-particle scene: r = 0.75 mm, rho = 1750, falling at 1 m/s from z = 2 mm.
constexpr double kRadius = 0.75e-3;
constexpr double kDensity = 1750;
const double kMass = kDensity * 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;
constexpr double kGravity = 9.81;

std::unique_ptr<Engine> singleParticle() {
  auto e = std::make_unique<Engine>(MPI_COMM_WORLD, std::filesystem::current_path());
  e->runScript(dataDir() / "in.single_particle");
  e->installCoupling();
  return e;
}

}  // namespace

// A grain hits the wall at ~1 m/s; speed out / speed in, both taken when the sphere touches
// the wall plane (z = r), must equal the configured restitution 0.3 within 3 %.
TEST(Engine, ReboundOnWallHasConfiguredRestitution) {
  ScratchDir dir;
  auto e = singleParticle();
  double v_in = 0, v_out = 0;
  bool in_contact = false;
  for (int chunk = 0; chunk < 600 && v_out == 0; ++chunk) {
    const State before = e->state();
    e->advance(5);
    const State s = e->state();
    ASSERT_EQ(s.ids.size(), 1u);
    const double z0 = before.position[2], z1 = s.position[2];
    // interpolate the velocity linearly to the crossing of z = r
    auto at_crossing = [&] {
      const double w = (kRadius - z0) / (z1 - z0);
      return before.velocity[2] + w * (s.velocity[2] - before.velocity[2]);
    };
    if (!in_contact && z1 < kRadius) {
      in_contact = true;
      v_in = at_crossing();
    } else if (in_contact && z1 > kRadius) {
      v_out = at_crossing();
    }
  }
  ASSERT_LT(v_in, -0.9);
  ASSERT_GT(v_out, 0.0) << "no rebound within 3 ms";
  const double e_measured = -v_out / v_in;
  std::printf("rebound: v_in %.5f m/s, v_out %.5f m/s, e = %.4f\n", v_in, v_out, e_measured);
  EXPECT_NEAR(e_measured, 0.3, 0.03 * 0.3) << "v_in " << v_in << " v_out " << v_out;
}

// Under gravity and drag F = K (u_f - v) the grain reaches v_t = u_f - m g / K (z up):
// checked within 0.5 % of the slip m g / K, for a relaxation time tau = m / K of 1 ms (1000 DEM
// steps) and a stiff one of 0.1 us (a tenth of the DEM step), where an explicit drag force
// would diverge. The transient at t = tau must follow v_t + (v0 - v_t) exp(-t/tau).
TEST(Engine, DragRelaxesToTerminalVelocity) {
  ScratchDir dir;
  for (double tau : {1e-3, 1e-7}) {
    auto e = singleParticle();
    e->command("unfix floor");  // free flight
    e->command("set atom 1 z 0.025");
    e->command("velocity all set 0 0 0");
    const double K = kMass / tau;
    const double uf[3] = {0.2, -0.1, 0.5};
    Terms t;
    t.ids = {1};
    t.drag_coefficient = {K};
    t.fluid_velocity = {uf[0], uf[1], uf[2]};
    const double vt = uf[2] - kMass * kGravity / K;
    const double slip = kMass * kGravity / K;
    if (tau > 1e-5) {
      e->applyTerms(t);
      e->advance(1000);  // t = tau
      const double expect = vt + (0.0 - vt) * std::exp(-1.0);
      EXPECT_NEAR(e->state().velocity[2], expect, 0.005 * std::abs(expect - 0.0))
          << "transient at t = tau";
      EXPECT_NEAR(e->state().velocity[0], uf[0] * (1 - std::exp(-1.0)), 0.005 * uf[0]);
    }
    for (int k = 0; k < 5; ++k) {  // 5 coupling intervals of 2 ms, terms re-sent each time
      e->applyTerms(t);
      e->advance(2000);
    }
    const State s = e->state();
    EXPECT_NEAR(s.velocity[2], vt, 0.005 * slip) << "tau = " << tau;
    EXPECT_NEAR(s.velocity[0], uf[0], 0.005 * slip) << "tau = " << tau;
    EXPECT_NEAR(s.velocity[1], uf[1], 0.005 * slip) << "tau = " << tau;
  }
}

// Drag and an explicit force together: v_t = u_f + (F - m g)/K, here with F = 0.4 m g upwards
// and tau = m/K = 0.5 ms: v_t = 0.3 - 0.6 g tau (z up).
TEST(Engine, DragWithExplicitForceTerminalVelocity) {
  ScratchDir dir;
  auto e = singleParticle();
  e->command("unfix floor");
  e->command("set atom 1 z 0.025");
  e->command("velocity all set 0 0 0");
  const double tau = 5e-4, K = kMass / tau;
  Terms t;
  t.ids = {1};
  t.drag_coefficient = {K};
  t.fluid_velocity = {0, 0, 0.3};
  t.explicit_force = {0, 0, 0.4 * kMass * kGravity};
  for (int k = 0; k < 10; ++k) {  // 10 ms = 20 tau
    e->applyTerms(t);
    e->advance(1000);
  }
  const double vt = 0.3 - 0.6 * kGravity * tau;
  EXPECT_NEAR(e->state().velocity[2], vt, 0.005 * 0.6 * kGravity * tau);
}

// An explicit force alone (no K) accelerates the particle like any other force: with
// F = m g upwards the grain floats at constant velocity.
TEST(Engine, ExplicitForceWithoutDrag) {
  ScratchDir dir;
  auto e = singleParticle();
  e->command("unfix floor");
  e->command("set atom 1 z 0.025");
  e->command("velocity all set 0 0 0.1");
  Terms t;
  t.ids = {1};
  t.explicit_force = {0, 0, kMass * kGravity};
  e->applyTerms(t);
  e->advance(2000);
  const State s = e->state();
  EXPECT_NEAR(s.velocity[2], 0.1, 1e-9);
  EXPECT_NEAR(s.position[2], 0.025 + 0.1 * 2000 * 1e-6, 1e-9);
  // Next interval without terms: back to free fall, v = 0.1 - g t.
  e->applyTerms(Terms{});
  e->advance(1000);
  EXPECT_NEAR(e->state().velocity[2], 0.1 - kGravity * 1e-3, 1e-9);
}

// Coating increments land on the particle with that id, accumulate, do not change the
// mechanical mass, and survive a LIGGGHTS restart file.
TEST(Engine, CoatingMassByIdAndThroughRestart) {
  ScratchDir dir;
  std::filesystem::path restart;
  {
    Engine e(MPI_COMM_WORLD, dir.path());
    e.runScript(dataDir() / "in.settling_bed");
    e.installCoupling();
    e.advance(1);  // insert the particles
    State s = e.state();
    ASSERT_EQ(s.ids.size(), 1000u);
    Terms t;
    t.ids = s.ids;
    for (auto id : s.ids) t.coating_increment.push_back(1e-9 * static_cast<double>(id));
    e.applyTerms(t);
    e.advance(500);   // particles move (fall) in between
    e.applyTerms(t);  // second increment
    s = e.state();
    for (std::size_t k = 0; k < s.ids.size(); ++k) {
      ASSERT_DOUBLE_EQ(s.coating_mass[k], 2e-9 * static_cast<double>(s.ids[k]))
          << "id " << s.ids[k];
      ASSERT_NEAR(s.mass[k], 2500 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.0015, 3), 1e-15);
    }
    restart = e.writeRestart(dir.path() / "cp" / "liggghts.restart");
  }
  ASSERT_TRUE(std::filesystem::exists(restart));
  // A script that continues from the restart file.
  std::ofstream(dir.path() / "in.restart")
      << "atom_style granular\natom_modify map array\n"
         "boundary f f f\nnewton off\ncommunicate single vel yes\nunits si\nread_restart "
      << restart.string()
      << "\n"
         "neighbor 0.001 bin\n"
         "fix m1 all property/global youngsModulus peratomtype 5e6\n"
         "fix m2 all property/global poissonsRatio peratomtype 0.3\n"
         "fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3\n"
         "fix m4 all property/global coefficientFriction peratomtypepair 1 0.52\n"
         "pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 3e-5\n"
         "fix integr all nve/sphere\n";
  Engine e(MPI_COMM_WORLD, dir.path());
  e.runScript(dir.path() / "in.restart");
  e.installCoupling();
  const State s = e.state();
  ASSERT_EQ(s.ids.size(), 1000u);
  for (std::size_t k = 0; k < s.ids.size(); ++k)
    ASSERT_DOUBLE_EQ(s.coating_mass[k], 2e-9 * static_cast<double>(s.ids[k])) << "id " << s.ids[k];
}

// Terms naming a particle LIGGGHTS does not have, twice, or with K < 0 are refused by name.
TEST(Engine, BadTermsAreRefusedWithTheParticleId) {
  ScratchDir dir;
  auto e = singleParticle();
  Terms t;
  t.ids = {7};
  t.coating_increment = {1e-9};
  try {
    e->applyTerms(t);
    FAIL() << "unknown id accepted";
  } catch (const std::runtime_error& err) {
    EXPECT_NE(std::string(err.what()).find("does not have: 7"), std::string::npos) << err.what();
  }
  t.ids = {1, 1};
  t.coating_increment = {1e-9, 1e-9};
  EXPECT_THROW(e->applyTerms(t), std::runtime_error);
  t.ids = {1};
  t.coating_increment = {};
  t.drag_coefficient = {-1};
  t.fluid_velocity = {0, 0, 0};
  EXPECT_THROW(e->applyTerms(t), std::runtime_error);
}

// The timestep report reads the script's materials: the 1.5 mm grain has
// t_R = 7.680e-5 s (hand calculation in timestep_laws_test.cpp), so dt = 1e-6 is 0.0130 t_R.
TEST(Engine, TimestepReportUsesScriptMaterials) {
  ScratchDir dir;
  auto e = singleParticle();
  const TimestepReport r = e->timestepReport(2.0);
  ASSERT_TRUE(r.has_particles);
  EXPECT_NEAR(r.min_radius, kRadius, 1e-12);
  EXPECT_NEAR(r.rayleigh_time, 7.680e-5, 0.002e-5);
  EXPECT_NEAR(r.dtOverRayleigh(), 1e-6 / 7.680e-5, 1e-4);
}

// A typo in the script: LIGGGHTS' own message comes back as an exception with the script
// line, instead of LIGGGHTS ending the process.
TEST(Engine, MalformedScriptSurfacesLiggghtsMessage) {
  ScratchDir dir;
  Engine e(MPI_COMM_WORLD, dir.path());
  try {
    e.runScript(dataDir() / "in.malformed");
    FAIL() << "malformed script accepted";
  } catch (const LiggghtsError& err) {
    const std::string msg = err.what();
    EXPECT_NE(msg.find("ERROR"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Invalid fix style"), std::string::npos) << msg;
    EXPECT_NE(msg.find("in.malformed, line 7"), std::string::npos) << msg;
    EXPECT_FALSE(err.collectiveBroken());
  }
  EXPECT_TRUE(e.broken());
}

// The mechanism behind the error capture: inside a LiggghtsCall, MPI_Abort (LIGGGHTS
// error->one) and MPI_Finalize (error->all) throw instead of ending the process; outside, they
// are the library's (not called here: they would end the test).
TEST(LiggghtsCallScope, FinalizeAndAbortThrowInside) {
  {
    LiggghtsCall call;
    try {
      MPI_Abort(MPI_COMM_WORLD, 3);
      FAIL() << "MPI_Abort returned";
    } catch (const LiggghtsStop& stop) {
      EXPECT_TRUE(stop.aborted);
    }
    try {
      MPI_Finalize();
      FAIL() << "MPI_Finalize returned";
    } catch (const LiggghtsStop& stop) {
      EXPECT_FALSE(stop.aborted);
    }
  }
  int finalized = 1;
  MPI_Finalized(&finalized);
  EXPECT_EQ(finalized, 0) << "MPI must still be usable";
}
