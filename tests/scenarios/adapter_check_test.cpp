// `cosim validate` asks each adapter about the scene through --check-options (issue 15): what
// the run would refuse only after starting its solvers is refused before anything starts, with
// the scenario file, the participant and the adapter's reason; nothing is left behind.
#include "adapter_check.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cosim/models/registry.h"
#include "plan.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kBed = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/scenario.yaml";

// A private TMPDIR for each test: the check's temporary folder must be gone afterwards.
class AdapterCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_ = fs::temp_directory_path() / ("cosim-adapter-check-test-" + std::to_string(getpid()));
    fs::remove_all(tmp_);
    fs::create_directories(tmp_);
    old_ = std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "";
    setenv("TMPDIR", tmp_.c_str(), 1);
  }
  void TearDown() override {
    if (old_.empty())
      unsetenv("TMPDIR");
    else
      setenv("TMPDIR", old_.c_str(), 1);
    EXPECT_TRUE(fs::is_empty(tmp_)) << "the check left files in " << tmp_;
    fs::remove_all(tmp_);
  }
  // The lines of an accepted scene; a failure if it is refused.
  std::vector<std::string> accepted(const fs::path& file, const std::vector<std::string>& sets) {
    Scenario sc = loadScenario(file, sets);
    cosim::models::SceneModels m = makeModels(sc);
    return checkAdapters(sc, makePlan(sc, m));
  }
  // The reason of a refusal; a failure if it is accepted.
  std::string refusal(const fs::path& file, const std::vector<std::string>& sets,
                      double timeout_s = kAdapterCheckSeconds) {
    Scenario sc = loadScenario(file, sets);
    cosim::models::SceneModels m = makeModels(sc);
    try {
      checkAdapters(sc, makePlan(sc, m), timeout_s);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted: " << file;
    return "";
  }
  fs::path tmp_;
  std::string old_;
};

void expectFragments(const std::string& msg, const std::vector<std::string>& fragments) {
  for (const auto& f : fragments)
    EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' missing in: " << msg;
}

// A scene file `text` in a fresh folder beside copies of the bed's case folders.
fs::path sceneCopy(const fs::path& where) {
  fs::create_directories(where);
  const fs::path src = kBed.parent_path();
  fs::copy(src / "cfd", where / "cfd", fs::copy_options::recursive);
  fs::copy(src / "dem", where / "dem", fs::copy_options::recursive);
  fs::copy(kBed, where / "scenario.yaml");
  return where / "scenario.yaml";
}

}  // namespace

TEST_F(AdapterCheck, TheShippedBedIsAcceptedByBothRealAdapters) {
  const auto lines = accepted(kBed, {});
  ASSERT_EQ(lines.size(), 2u);
  expectFragments(lines[0], {"fluid", "openfoam", "accepts"});
  expectFragments(lines[1], {"particles", "liggghts", "accepts"});
}

TEST_F(AdapterCheck, AScriptTimeStepThatDoesNotFitTheCouplingIsRefusedWithTheFix) {
  // in.liggghts says timestep ${cfd_dt/dem_steps}: templated with dem_steps 10 it is 1e-5 s,
  // while the coupling now asks for 1e-4 / 8 = 1.25e-5 s
  const auto msg = refusal(kBed, {"coupling.dem_steps=8"});
  expectFragments(msg, {kBed.string(), "participants.particles", "liggghts", "timestep 1e-05",
                        "1.25e-05", "coupling.dem_steps: 10"});
}

TEST_F(AdapterCheck, AMissingScriptAndAMissingWallMeshAreNamed) {
  expectFragments(refusal(kBed, {"participants.particles.options.script=in.missing"}),
                  {"participants.particles", "options.script", "in.missing", "files: folder"});
  const fs::path copy = sceneCopy(tmp_ / "scene");
  fs::remove(copy.parent_path() / "dem/nozzle.stl");
  const auto msg = refusal(copy, {});
  expectFragments(msg, {"in.liggghts, line 36", "mesh/surface", "nozzle.stl"});
  fs::remove_all(tmp_ / "scene");
}

TEST_F(AdapterCheck, TheFluidsPatchesMeshAndRanksAreChecked) {
  expectFragments(
      refusal(kBed, {"participants.fluid.options.inlet_patches=[distributer]"}),
      {"participants.fluid", "inlet_patches", "no patch 'distributer'", "system/blockMeshDict"});
  expectFragments(refusal(kBed, {"participants.fluid.options.outlet_patches=[top]"}),
                  {"outlet_patches", "no patch 'top'"});
  // The message names the case folder of the scene, not the check's temporary copy
  const auto mesh = refusal(kBed, {"participants.fluid.options.mesh=existing"});
  expectFragments(mesh, {"options.mesh is 'existing'",
                         (kBed.parent_path() / "cfd").string() + "/constant/polyMesh"});
  EXPECT_EQ(mesh.find("cosim-validate-"), std::string::npos) << mesh;
  expectFragments(refusal(kBed, {"participants.fluid.mpi=3"}),
                  {"numberOfSubdomains is 2", "3 MPI ranks", "make them equal"});
  expectFragments(refusal(kBed, {"participants.fluid.options.min_voidage=2"}),
                  {"participants.fluid", "min_voidage",
                   "(this participant's settings include the command line's --set "
                   "participants.fluid.options.min_voidage=2)"});
  // The shipped decomposition (2 subdomains) on 2 ranks is accepted
  expectFragments(accepted(kBed, {"participants.fluid.mpi=2"})[0], {"on 2 MPI ranks"});
}

TEST_F(AdapterCheck, TheAnalyticAdaptersCheckTheirOptionsToo) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/settling-sphere/scenario.yaml";
  EXPECT_EQ(accepted(scene, {}).size(), 2u);
  expectFragments(refusal(scene, {"participants.fluid.options.voidage=2"}),
                  {"participants.fluid", "analytic-fluid", "voidage"});
  expectFragments(refusal(scene, {"participants.particles.options.colour=red"}),
                  {"participants.particles", "free-particles", "colour"});
}

TEST_F(AdapterCheck, AnAdapterThatDoesNotAnswerIsStoppedAndNamed) {
  const fs::path hang = tmp_ / "hang.sh";
  {
    std::ofstream out(hang);
    out << "#!/bin/sh\nsleep 30\n";
  }
  fs::permissions(hang, fs::perms::owner_all);
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/settling-sphere/scenario.yaml";
  const auto t0 = std::chrono::steady_clock::now();
  const auto msg = refusal(scene, {"participants.fluid.command=" + hang.string()}, 1.0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  expectFragments(msg, {"participants.fluid", "did not answer --check-options within 1 s"});
  fs::remove(hang);
}

TEST_F(AdapterCheck, ACustomAdapterIsNotAskedAndSaysSo) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/settling-sphere/scenario.yaml";
  const auto lines = accepted(
      scene, {"participants.fluid.adapter=my-fluid", "participants.fluid.command=/bin/false"});
  expectFragments(lines.at(0), {"fluid", "not checked", "custom adapter 'my-fluid'"});
}
