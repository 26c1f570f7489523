// launch: mpirun with a host file, with the real solvers: the fluid on 2 ranks and the particles
// on 1, each started by cosim as `mpirun -np N --hostfile FILE` (this host, named in the file).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cosim/analysis/files.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(Mpirun, BothParticipantsStartedWithAHostFileRunOnTheirRanks) {
  const fs::path base = fs::temp_directory_path() / ("cosim-mpirun-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  std::ofstream(base / "hosts") << "localhost slots=3\n";
  // hostfile: is relative to the scenario file; an absolute path is taken as it is
  Scenario sc = loadScenario(
      fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml",
      {"coupling.end_time=0.002", "participants.fluid.launch=mpirun", "participants.fluid.mpi=2",
       "participants.fluid.hostfile=" + (base / "hosts").string(),
       "participants.particles.launch=mpirun",
       "participants.particles.hostfile=" + (base / "hosts").string()});
  RunOptions o;
  o.quiet = true;
  o.output = base / "run";
  const RunResult r = Coupler(std::move(sc), o).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  std::ifstream in(base / "run/cosim.log");
  std::stringstream log;
  log << in.rdbuf();
  for (const char* started : {"started fluid (mpirun: 2 MPI ranks on the hosts of",
                              "started particles (mpirun: 1 process on the hosts of"}) {
    EXPECT_NE(log.str().find(started), std::string::npos) << log.str();
  }
  EXPECT_NE(log.str().find("--hostfile"), std::string::npos);
  EXPECT_TRUE(fs::is_directory(base / "run/fluid/processor1"));
  EXPECT_EQ(cosim::analysis::readJsonFile(base / "run/summary.json").at("status"), "completed");
  fs::remove_all(base);
}
