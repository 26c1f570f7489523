// How cosim starts a participant (participants.<name>.launch): the command line in front of the
// adapter's own for local, mpirun and slurm, and the scenario's errors for the launch keys. The
// real launches are tested with the real solvers in tests/scenarios/slurm_test.cpp (srun) and
// tests/scenarios/plasma_coating_ci_test.cpp (mpirun).
#include "launchers.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cosim/util/host_memory.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const std::string kScene = R"(
name: launch
participants:
  fluid: { adapter: analytic-fluid, options: { velocity: [0, 0, 0.1] } }
  particles: { adapter: free-particles, LAUNCH options: { density: 2500 } }
coupling: { dt: 1.0e-4, dem_steps: 10, end_time: 0.01 }
models:
  drag: { law: stokes }
)";

fs::path dir() { return fs::temp_directory_path(); }

Scenario parse(const std::string& launch) {
  std::string s = kScene;
  s.replace(s.find("LAUNCH "), 7, launch);
  return parseScenario(s, dir() / "launch.yaml", {}, {});
}

std::string errorOf(const std::string& launch) {
  try {
    parse(launch);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "(accepted)";
}

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

TEST(Launchers, LocalSingleRankHasNoLauncher) {
  const Scenario sc = parse("");
  EXPECT_TRUE(launcherPrefix("particles", sc.participants.at("particles")).empty());
  EXPECT_NE(describeLaunch(sc.participants.at("particles")).find("local"), std::string::npos);
}

TEST(Launchers, SlurmIsAnSrunStepWithOnlyTheCpusAskedFor) {
  const Scenario sc = parse(
      "launch: slurm, mpi: 4, slurm: { nodes: 2, nodelist: 'n[1-2]', args: [--cpus-per-task=2] "
      "}, ");
  const auto argv = launcherPrefix("particles", sc.participants.at("particles"));
  ASSERT_FALSE(argv.empty());
  EXPECT_EQ(fs::path(argv[0]).filename(), "srun");
  for (const char* a : {"--ntasks=4", "--nodes=2", "--nodelist=n[1-2]", "--exact", "--mpi=pmix",
                        "--kill-on-bad-exit=1", "--cpus-per-task=2"}) {
    EXPECT_TRUE(contains(argv, a)) << a;
  }
  // the user's own choices win over the defaults
  const Scenario own = parse("launch: slurm, slurm: { args: [--overlap, --mpi=pmi2] }, ");
  const auto argv2 = launcherPrefix("particles", own.participants.at("particles"));
  EXPECT_FALSE(contains(argv2, "--exact"));
  EXPECT_FALSE(contains(argv2, "--mpi=pmix"));
  EXPECT_TRUE(contains(argv2, "--mpi=pmi2"));
}

TEST(Launchers, MpirunTakesTheHostFileRelativeToTheScenario) {
  const fs::path hosts = dir() / ("cosim-hosts-" + std::to_string(::getpid()));
  std::ofstream(hosts) << "localhost slots=2\n";
  const Scenario sc =
      parse("launch: mpirun, mpi: 2, hostfile: " + hosts.filename().string() + ", ");
  const auto argv = launcherPrefix("particles", sc.participants.at("particles"));
  ASSERT_GE(argv.size(), 3u);
  EXPECT_EQ(fs::path(argv[0]).filename(), "mpirun");
  EXPECT_TRUE(contains(argv, "--hostfile"));
  EXPECT_TRUE(contains(argv, hosts.string()));
  EXPECT_FALSE(contains(argv, "--oversubscribe"));
  fs::remove(hosts);
}

TEST(Launchers, LaunchKeysAreCheckedAndErrorsGiveTheRemedy) {
  EXPECT_NE(errorOf("launch: cluster, ").find("'slurm' (with srun"), std::string::npos);
  EXPECT_NE(errorOf("slurm: { nodes: 2 }, ").find("only used with launch: slurm"),
            std::string::npos);
  EXPECT_NE(errorOf("launch: slurm, slurm: { nodes: 1.5 }, ").find("whole number of nodes"),
            std::string::npos);
  EXPECT_NE(errorOf("launch: slurm, slurm: { args: [pmix] }, ").find("starting with '-'"),
            std::string::npos);
  EXPECT_NE(errorOf("launch: slurm, slurm: { partition: x }, ").find("partition"),
            std::string::npos);
  EXPECT_NE(errorOf("launch: mpirun, hostfile: no-such-hosts, ").find("does not exist"),
            std::string::npos);
  EXPECT_NE(errorOf("hostfile: h, ").find("only used with launch: mpirun"), std::string::npos);
  EXPECT_NE(errorOf("workdir: scratch, ").find("expected an absolute folder"), std::string::npos);
  EXPECT_NE(errorOf("launch: external, workdir: /scratch, ").find("--workdir DIR"),
            std::string::npos);
}

TEST(Launchers, MoreRanksOnThisHostThanItsMemoryHoldsAreRefused) {
  // 50 MB a rank at the least: the host's memory in MB, plus one, cannot start here
  const long ranks = std::min(4096L, static_cast<long>(cosim::util::hostMemoryBytes() / 50e6) + 1);
  if (ranks * 50e6 <= cosim::util::hostMemoryBytes()) GTEST_SKIP() << "a host with over 200 GB";
  const std::string mpi = "mpi: " + std::to_string(ranks) + ", ";
  const auto local = errorOf(mpi);
  EXPECT_NE(local.find(std::to_string(ranks) + " MPI ranks on this host need at least"),
            std::string::npos)
      << local;
  EXPECT_NE(local.find("launch: slurm"), std::string::npos) << local;
  EXPECT_NE(errorOf("launch: mpirun, " + mpi).find("MPI ranks on this host"), std::string::npos);
  // spread over nodes, the same count is the scheduler's to place
  EXPECT_EQ(errorOf("launch: slurm, " + mpi), "(accepted)");
  EXPECT_EQ(errorOf("launch: external, " + mpi), "(accepted)");
}

TEST(Launchers, AFolderOfItsOwnIsPassedAsWorkdirPerRunAndParticipant) {
  const Scenario sc = parse("launch: slurm, workdir: /scratch/cosim, ");
  EXPECT_EQ(sc.participants.at("particles").workdir, "/scratch/cosim");
  EXPECT_TRUE(sc.participants.at("fluid").workdir.empty());
}
