// launch: slurm with a real Slurm: a one-node cluster on this machine (scripts/local-slurm.sh:
// munged, slurmctld and slurmd with their own configuration in a private folder), an allocation
// made with salloc, and both participants started by cosim as srun job steps inside it. The CI
// coating bed run that way must be the run cosim launches locally, to the bit. A machine where
// the cluster cannot start fails these tests with the script's own words, never skips them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/time_series.h"
#include "cosim/util/child_process.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = COSIM_SOURCE_DIR;

std::string text(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Slurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("cosim-slurm-test-" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    const fs::path log = base_ / "local-slurm.log";
    const int code = cosim::util::runProgram(
        {"bash", (kSource / "scripts/local-slurm.sh").string(), "start"}, log);
    why_ = code == 0 ? ""
                     : "scripts/local-slurm.sh start failed (" + std::to_string(code) + "):\n" +
                           text(log);
    const std::string out = text(log);
    const auto at = out.rfind("export SLURM_CONF=");
    if (why_.empty() && at == std::string::npos)
      why_ = "no SLURM_CONF from local-slurm.sh:\n" + out;
    if (why_.empty()) {
      std::string conf = out.substr(at + std::string("export SLURM_CONF=").size());
      conf = conf.substr(0, conf.find('\n'));
      ::setenv("SLURM_CONF", conf.c_str(), 1);
    }
  }
  // The cluster is left running (another test process may be using it; `scripts/local-slurm.sh
  // stop` ends it, and so does the end of a CI run).
  static void TearDownTestSuite() { fs::remove_all(base_); }
  // `cosim run` inside a fresh allocation of `tasks` CPUs, the participants launched by srun.
  static int runInAllocation(int tasks, const std::string& folder, std::vector<std::string> sets) {
    std::vector<std::string> argv = {"salloc",
                                     "-n",
                                     std::to_string(tasks),
                                     "--quiet",
                                     "--time=15",
                                     (fs::path(COSIM_BINARY_DIR) / "cosim").string(),
                                     "run",
                                     (kSource / "scenarios/plasma-coating-bed/ci.yaml").string(),
                                     "-o",
                                     (base_ / folder).string(),
                                     "--quiet"};
    for (const auto& s : sets) {
      argv.push_back("--set");
      argv.push_back(s);
    }
    return cosim::util::runProgram(argv, base_ / (folder + ".out"));
  }
  static inline fs::path base_;
  static inline std::string why_;
};

const std::vector<std::string> kBySrun = {"participants.fluid.launch=slurm",
                                          "participants.particles.launch=slurm",
                                          "coupling.end_time=0.02"};

}  // namespace

TEST_F(Slurm, BothParticipantsAsJobStepsGiveTheLocalRunToTheBit) {
  ASSERT_TRUE(why_.empty()) << why_;
  ASSERT_EQ(runInAllocation(2, "srun", kBySrun), 0) << text(base_ / "srun.out");
  const std::string log = text(base_ / "srun" / "cosim.log");
  for (const char* who : {"started fluid (slurm: srun", "started particles (slurm: srun"}) {
    EXPECT_NE(log.find(who), std::string::npos) << log;
  }
  EXPECT_NE(log.find("as a step of Slurm job"), std::string::npos) << log;

  RunOptions o;
  o.quiet = true;
  o.output = base_ / "local";
  RunResult local = Coupler(loadScenario(kSource / "scenarios/plasma-coating-bed/ci.yaml",
                                         {"coupling.end_time=0.02"}),
                            o)
                        .run();
  ASSERT_EQ(local.exit_code, 0) << local.message;
  const auto a = cosim::analysis::readJsonFile(base_ / "srun" / "summary.json");
  const auto b = cosim::analysis::readJsonFile(base_ / "local" / "summary.json");
  EXPECT_EQ(a.at("status"), "completed");
  EXPECT_EQ(a.at("headline"), b.at("headline"));
  EXPECT_EQ(a.at("extra").at("observables"), b.at("extra").at("observables"));
  const auto sa = cosim::analysis::readTimeSeries(base_ / "srun" / "timeseries.csv");
  const auto sb = cosim::analysis::readTimeSeries(base_ / "local" / "timeseries.csv");
  ASSERT_EQ(sa.rows(), sb.rows());
  for (const char* column :
       {"time", "particle_count", "precursor_in", "precursor_out", "precursor_held",
        "precursor_removed", "coated_mass", "pressure_drop"}) {
    const auto& x = sa.at(column);
    const auto& y = sb.at(column);
    for (std::size_t i = 0; i < x.size(); ++i) {
      // bit for bit; a value not defined yet (the first row's pressure drop) is NaN in both
      if (!(std::isnan(x[i]) && std::isnan(y[i]))) ASSERT_EQ(x[i], y[i]) << column << " row " << i;
    }
  }
}

// Two ranks of the fluid started by srun (PMIx) run decomposed, as under mpirun.
TEST_F(Slurm, ADecomposedFluidStartedBySrunRunsOnItsRanks) {
  ASSERT_TRUE(why_.empty()) << why_;
  std::vector<std::string> sets = kBySrun;
  sets.back() = "coupling.end_time=0.002";
  sets.push_back("participants.fluid.mpi=2");
  // three ranks in an allocation of two CPUs: the steps share them (srun --overlap)
  sets.push_back("participants.fluid.slurm={args: [--overlap]}");
  sets.push_back("participants.particles.slurm={args: [--overlap]}");
  ASSERT_EQ(runInAllocation(2, "srun-mpi", sets), 0) << text(base_ / "srun-mpi.out");
  EXPECT_NE(text(base_ / "srun-mpi" / "fluid.log").find("nProcs : 2"), std::string::npos);
  EXPECT_TRUE(fs::is_directory(base_ / "srun-mpi" / "fluid" / "processor1"));
  EXPECT_EQ(cosim::analysis::readJsonFile(base_ / "srun-mpi" / "summary.json").at("status"),
            "completed");
}
