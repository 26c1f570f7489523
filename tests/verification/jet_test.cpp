// Verification 4c: a jet carries the particle out of the domain through the open outlet
// (scenarios/verify-jet): the run completes, the particle is counted as deleted, the final
// population is empty and nothing is NaN. Hand estimate: gas 3 m/s, terminal slip 0.859 m/s,
// so the sphere rises at up to 2.14 m/s and leaves the 0.15 m column (launched at 0.05 m)
// well before 0.2 s (at most 0.1 m / (3 - 0.859 - ...) ~ 0.05-0.1 s).
#include <gtest/gtest.h>

#include <cmath>

#include "run_scene.h"

using cosim::verification::runScene;

TEST(Jet, ParticleBlownOutThroughTheOutletIsCountedAndTheRunCompletes) {
  auto r = runScene("verify-jet", {}, "jet");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(r.steps, 200u);
  EXPECT_EQ(r.final_state.size(), 0u);
  ASSERT_TRUE(r.totals.count("particles_deleted"));
  EXPECT_EQ(r.totals.at("particles_deleted"), 1.0);
  for (const auto& [name, value] : r.totals) EXPECT_TRUE(std::isfinite(value)) << name;
}
