// Hertz contact time and the dt verdict against hand calculations.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/liggghts/hertz_contact_time.h"
#include "cosim/liggghts/timestep_check.h"

using namespace cosim::liggghts;

// The Rayleigh time itself (cosim/util/rayleigh_time.h) is tested in tests/util.

// Two paper grains at 1 m/s: m = 1750 * 4/3 pi (7.5e-4)^3 = 3.0925e-6 kg, m_eff = 1.5463e-6,
// r_eff = 3.75e-4, E_eff = 5e6 / (2 * 0.91) = 2.7473e6 Pa.
// m_eff^2 / (r_eff E_eff^2 v) = 2.3909e-12 / (3.75e-4 * 7.5475e12) = 8.4478e-22;
// ^0.2 = 6.1002e-5; * 2.87 = 1.7508e-4 s.
TEST(HertzContactTime, IdenticalPaperGrainsAt1ms) {
  EXPECT_NEAR(hertzContactTimeIdenticalSpheres(0.75e-3, 1750, 5e6, 0.3, 1.0), 1.7508e-4, 0.0005e-4);
}

// Against a rigid wall: m_eff = m, r_eff = r, E_eff = E/(1-nu^2); the ratio to the
// identical-sphere time is (1/2)^0.2 = 0.87055 (m_eff^2 x4, r_eff x2, E_eff^2 x4: 4/(2*4)).
TEST(HertzContactTime, RigidWallIsShorterByTwoToTheMinusOneFifth) {
  const double pp = hertzContactTimeIdenticalSpheres(1e-3, 2500, 1e7, 0.25, 2.0);
  const double wall = hertzContactTimeRigidWall(1e-3, 2500, 1e7, 0.25, 2.0);
  EXPECT_NEAR(wall / pp, std::pow(0.5, 0.2), 1e-12);
  // and v^-1/5: doubling the speed shortens the contact by 2^-0.2
  EXPECT_NEAR(hertzContactTimeRigidWall(1e-3, 2500, 1e7, 0.25, 4.0) / wall, std::pow(0.5, 0.2),
              1e-12);
}

TEST(TimestepVerdict, Thresholds) {
  TimestepReport r;
  r.has_particles = true;
  r.rayleigh_time = 1e-4;
  r.hertz_time = 3e-4;
  r.impact_speed = 2;
  r.min_radius = 1e-3;
  r.dt = 1e-5;  // 0.1 t_R, t_H/30
  EXPECT_EQ(judgeTimestep(r).verdict, Verdict::ok);
  r.dt = 2.5e-5;  // 0.25 t_R
  EXPECT_EQ(judgeTimestep(r).verdict, Verdict::doubtful);
  r.dt = 3.1e-5;  // 0.31 t_R
  const auto v = judgeTimestep(r);
  EXPECT_EQ(v.verdict, Verdict::unstable);
  EXPECT_DOUBLE_EQ(v.suggested_dt, 2e-5);  // min(0.2 t_R, t_H/5) = min(2e-5, 6e-5)
  // Hertz-limited: t_H/3 < dt < 0.3 t_R
  r.hertz_time = 6e-5;
  r.dt = 2.1e-5;
  EXPECT_EQ(judgeTimestep(r).verdict, Verdict::unstable);
  EXPECT_DOUBLE_EQ(judgeTimestep(r).suggested_dt, 1.2e-5);
  EXPECT_NE(judgeTimestep(r).summary.find("0.35"), std::string::npos);  // dt/t_H printed
}
