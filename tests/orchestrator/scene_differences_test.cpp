// What a resume may change (docs/restarts.md, "Resuming"): the keys of the scene that the saved
// state does not depend on are not differences between a checkpoint's scene and the one it is
// resumed with; everything else is, named with both values.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "checkpoints.h"

using namespace cosim::orchestrator;

TEST(Checkpoint, OnlyWhatTheSavedStateDoesNotDependOnMayChangeOnResume) {
  const YAML::Node saved = YAML::Load(
      "coupling: {dt: 1.0e-4, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam, timeout: 60, options: {viscosity: 1.8e-5}}}\n");
  const YAML::Node now = YAML::Load(
      "coupling: {dt: 0.0001, end_time: 40}\n"
      "participants: {fluid: {adapter: openfoam, timeout: 3600,\n"
      "  options: {viscosity: 1.8e-5, solver_log_every: 100}}}\n");
  EXPECT_TRUE(sceneDifferences(saved, now).empty());
  const YAML::Node other = YAML::Load(
      "coupling: {dt: 1.0e-4, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam, timeout: 60, options: {viscosity: 2e-5}}}\n");
  const auto d = sceneDifferences(saved, other);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0], "participants.fluid.options.viscosity: 1.8e-5 -> 2e-5");
}
