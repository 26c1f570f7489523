// Checkpoint{path}: cosimFoam writes the current time folder (every field a restart needs) into
// path, per processor when decomposed, and names what it wrote; the run then goes on.
#include <gtest/gtest.h>

#include <filesystem>

#include "foam_harness.h"

namespace cosim::test {
namespace {
namespace fs = std::filesystem;

void checkpointRun(int ranks) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.1"},
                    {"inlet_precursor", "0.01"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.species = true;
  cfg.send = {"voidage", "precursor_removed"};
  cfg.receive = {"position", "radius", "transfer_coefficient"};
  cfg.ranks = ranks;
  FoamRun run(cfg);
  const auto particles = makeParticles({0.01, 0.01, 0.03, 0.01, 0.01, 0.07}, 1e-3);
  for (int k = 0; k < 3; ++k) {
    run.sample(particles);
    run.advance(1e-3, cosim::link::ParticleData{});
  }
  const fs::path where = fs::path(run.caseDir()) / "checkpoint-a";
  const auto files = run.checkpoint(where.string());
  ASSERT_EQ(files.size(), static_cast<std::size_t>(ranks));
  for (const auto& f : files) {
    EXPECT_EQ(fs::path(f).filename(), "0.003") << f;
    for (const char* field : {"p", "U", "voidage", "precursor", "phi"}) {
      EXPECT_TRUE(fs::exists(fs::path(f) / field)) << f << "/" << field;
    }
  }
  // The run goes on after a checkpoint
  run.sample(particles);
  const auto a = run.advance(1e-3, cosim::link::ParticleData{});
  EXPECT_GT(a.fluid().species().precursor_in(), 0.0);
  EXPECT_EQ(run.shutdown(), 0);
}

TEST(OpenFoamCheckpoint, WritesTheTimeFolderAndGoesOn) { checkpointRun(1); }
TEST(OpenFoamCheckpoint, WritesEveryProcessorWhenDecomposed) { checkpointRun(2); }

}  // namespace
}  // namespace cosim::test
