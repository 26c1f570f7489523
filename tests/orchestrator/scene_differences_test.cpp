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

// The coupling step may change on resume, the DEM step coupling.dt / coupling.dem_steps kept (the
// particle solver's restart holds it); the refusal names the dem_steps that keeps it.
TEST(Checkpoint, TheCouplingStepMayChangeOnResumeWhenTheDemStepStays) {
  const YAML::Node saved = YAML::Load(
      "coupling: {dt: 1.0e-4, dem_steps: 20, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam}, particles: {adapter: liggghts}}\n");
  const YAML::Node halved = YAML::Load(
      "coupling: {dt: 5.0e-5, dem_steps: 10, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam}, particles: {adapter: liggghts}}\n");
  EXPECT_TRUE(sceneDifferences(saved, halved).empty());
  EXPECT_EQ(refusedStepChange(saved, halved), "");
  EXPECT_EQ(refusedStepChange(saved, saved), "");
  const YAML::Node dem = YAML::Load(
      "coupling: {dt: 5.0e-5, dem_steps: 20, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam}, particles: {adapter: liggghts}}\n");
  const std::string why = refusedStepChange(saved, dem);
  EXPECT_NE(why.find("from 5e-06 to 2.5e-06 s"), std::string::npos) << why;
  EXPECT_NE(why.find("coupling.dem_steps=10"), std::string::npos) << why;
  // a step that is no whole number of DEM steps: what it must be a multiple of
  const YAML::Node odd = YAML::Load(
      "coupling: {dt: 7.0e-6, dem_steps: 1, end_time: 20}\n"
      "participants: {fluid: {adapter: openfoam}, particles: {adapter: liggghts}}\n");
  EXPECT_NE(refusedStepChange(saved, odd).find("a whole multiple of 5e-06 s"), std::string::npos)
      << refusedStepChange(saved, odd);
  // without particles there is no DEM step to keep
  const YAML::Node gas0 =
      YAML::Load("coupling: {dt: 1.0e-4, end_time: 1}\nparticipants: {fluid: {adapter: x}}\n");
  const YAML::Node gas1 =
      YAML::Load("coupling: {dt: 3.0e-5, end_time: 1}\nparticipants: {fluid: {adapter: x}}\n");
  EXPECT_EQ(refusedStepChange(gas0, gas1), "");
  // the peer path's overlapped scheme keeps the gas sampled ahead over the old step
  const YAML::Node peer = YAML::Load(
      "coupling: {dt: 5.0e-5, dem_steps: 10, end_time: 20, data_path: peer, scheme: overlapped}\n"
      "participants: {fluid: {adapter: openfoam}, particles: {adapter: liggghts}}\n");
  EXPECT_NE(refusedStepChange(saved, peer).find("overlapped"), std::string::npos);
}

// The clock: step k ends at start + k dt, rounded to 12 digits as every record carries it.
TEST(Checkpoint, TheStepClockCountsOnFromWhereTheStepChanged) {
  // 31,408 steps of 0.1 ms, then 0.05 ms: step 0 would lie at 3.1408 - 31408 x 5e-5 s
  const StepClock c{3.1408 - 31408 * 5e-5, 5e-5};
  EXPECT_EQ(c.time(31408), 3.1408);
  EXPECT_EQ(c.time(31409), 3.14085);
  EXPECT_EQ(c.time(31410), 3.1409);
  EXPECT_EQ(c.stepsTo(3.2), 31408u + 1184u);
}
