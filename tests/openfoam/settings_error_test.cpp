// Wrong settings give an error that names the key and says what was expected, sent to the
// orchestrator as wire::Error (not a hang, not a crash).
#include <gtest/gtest.h>

#include <string>

#include "foam_harness.h"

namespace cosim::test {
namespace {

std::string firstError(const FoamRunConfig& cfg) {
  try {
    FoamRun run(cfg);
    run.sample(makeParticles({0.01, 0.01, 0.05}, 1e-3));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

FoamRunConfig base() {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.1"},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.send = {"voidage"};
  cfg.receive = {"position", "radius"};
  return cfg;
}

TEST(OpenFoamSettings, UnknownOptionIsNamed) {
  auto cfg = base();
  cfg.options_yaml = "{min_voidage: 0.3, min_viodage: 0.4}";
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("participants.fluid.options.min_viodage: unknown option of cosimFoam; it "
                     "knows temperature, molar_mass"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("(docs/openfoam.md)"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, ALogIntervalThatIsNotAWholeNumberOfStepsIsRefused) {
  auto cfg = base();
  cfg.options_yaml = "{solver_log_every: 2.5}";
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("solver_log_every: expected a whole number from 1 to 1000000000, got 2.5"),
            std::string::npos)
      << msg;
  cfg.options_yaml = "{solver_log_every: 0}";
  EXPECT_NE(firstError(cfg).find("solver_log_every: expected a value in [1, 1000000000], got 0"),
            std::string::npos);
}

TEST(OpenFoamSettings, OutOfRangeValueSaysWhatIsExpected) {
  auto cfg = base();
  cfg.options_yaml = "{min_voidage: 1.5}";
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("min_voidage: expected a value in [0.01"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, UnknownPatchIsNamed) {
  auto cfg = base();
  cfg.options_yaml = "{inlet_patches: [distributor]}";
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("options.inlet_patches: no patch 'distributor'"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, PrecursorWithoutMassTransferIsRefused) {
  auto cfg = base();
  cfg.species = false;
  cfg.send = {"voidage", "precursor_fraction"};
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("no mass transfer"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, NonEulerTimeSchemeIsRefusedWithTheFile) {
  auto cfg = base();
  cfg.edits.push_back({"system/fvSchemes", "default Euler;", "default backward;"});
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("system/fvSchemes"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Euler"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, DecompositionNotMatchingTheRanksIsNamed) {
  // Two MPI ranks, a decomposeParDict for three: rank 0 refuses, every rank stops, no hang
  auto cfg = base();
  cfg.ranks = 2;
  cfg.edits.push_back(
      {"system/decomposeParDict", "numberOfSubdomains 2;", "numberOfSubdomains 3;"});
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("numberOfSubdomains is 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2 MPI ranks"), std::string::npos) << msg;
}

TEST(OpenFoamSettings, ABlockWithoutCellsIsNamedBeforeBlockMeshCrashes) {
  // blockMesh 1912 dies of a segmentation fault on a block with 0 cells in a direction (a cell
  // size larger than the block in a templated case): refused first, with the block and its count
  for (const char* counts : {"(5 0 25)", "(5 5 -1)", "(5 2.5 25)"}) {
    auto cfg = base();
    cfg.edits.push_back({"system/blockMeshDict", "(5 5 25)", counts});
    const auto msg = firstError(cfg);
    EXPECT_NE(msg.find("system/blockMeshDict, block 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cell count is"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("printStack"), std::string::npos) << msg;
  }
}

TEST(OpenFoamSettings, AMeshThatCannotFitInMemoryIsRefusedBeforeBlockMesh) {
  // 50,000^3 cells (a cell size far below the meant one): refused at once with the count, not
  // left to blockMesh to swap the machine to a standstill
  auto cfg = base();
  cfg.edits.push_back({"system/blockMeshDict", "(5 5 25)", "(50000 50000 50000)"});
  const auto msg = firstError(cfg);
  EXPECT_NE(msg.find("system/blockMeshDict: the mesh would have 1.25e+14 cells"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("GB of memory"), std::string::npos) << msg;
}

}  // namespace
}  // namespace cosim::test
