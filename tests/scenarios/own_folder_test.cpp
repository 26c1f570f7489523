// Participants that do not see the run folder (a node without a shared filesystem,
// docs/cluster.md): `participants.<name>.workdir` gives each a folder of its own, its case files
// and restart travel in the Welcome and its checkpoints come back in CheckpointWritten. Here
// each participant is started through a wrapper that puts it in a mount namespace of its own in
// which the run folder's parent is covered by an empty tmpfs and its working directory is `/`,
// so any file it took from the run folder would be missing. The run must still be the one with a
// shared folder, to the bit, and resume from its checkpoint.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/time_series.h"
#include "coupler.h"
#include "private_link.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kScene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";

// A wrapper that starts `real` with `hidden` covered by an empty tmpfs, from `/` (and, given a
// network namespace, inside it).
fs::path hidingWrapper(const fs::path& at, const fs::path& hidden, const fs::path& real,
                       const std::string& netns = "") {
  std::ofstream(at) << "#!/bin/sh\n"
                    << "exec " << (netns.empty() ? "" : "ip netns exec " + netns + " ")
                    << "unshare --mount --propagation private /bin/sh -c "
                    << "'mount -t tmpfs -o size=1m cosim-hidden \"$0\" && cd / && exec \"$@\"' '"
                    << hidden.string() << "' '" << real.string() << "' \"$@\"\n";
  fs::permissions(at, fs::perms::owner_all);
  return at;
}

RunResult run(const fs::path& out, std::vector<std::string> sets, const fs::path& resume = {}) {
  RunOptions o;
  o.quiet = true;
  if (resume.empty()) o.output = out;
  o.resume = resume;
  return Coupler(loadScenario(kScene, sets), o).run();
}

int shell(const std::string& command) { return std::system(command.c_str()); }

std::string text(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(OwnFolder, ParticipantsThatDoNotSeeTheRunFolderGiveTheSameRunAndResume) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-own-folder-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "runs");
  const fs::path bin = COSIM_BINARY_DIR;
  // the wrapper can cover a folder only where unshare and mount work (root, or a user namespace)
  ASSERT_EQ(std::system(("unshare --mount --propagation private /bin/sh -c 'mount -t tmpfs x " +
                         (base / "runs").string() + "' 2>" + (base / "unshare.err").string())
                            .c_str()),
            0)
      << "this machine cannot give a process a mount namespace of its own: "
      << text(base / "unshare.err");

  const std::vector<std::string> common = {"coupling.end_time=0.02", "coupling.scheme=parallel",
                                           "checkpoint.interval=0.01"};
  std::vector<std::string> hidden = common;
  std::vector<std::string> own = common;
  for (const char* name : {"fluid", "particles"}) {
    const fs::path real = bin / (std::string(name) == "fluid" ? "cosimFoam" : "cosim-liggghts");
    const std::string command =
        std::string("participants.") + name + ".command=" +
        hidingWrapper(base / (std::string(name) + ".sh"), base / "runs", real).string();
    hidden.push_back(command);
    own.push_back(command);
    own.push_back(std::string("participants.") + name + ".workdir=" + (base / "node").string());
  }
  // The wrapper does hide the run folder: without a folder of its own the adapters cannot find
  // their case (whichever says so first)
  const RunResult blind = run(base / "runs/blind", hidden);
  EXPECT_NE(blind.exit_code, 0);
  EXPECT_TRUE(blind.message.find("'in.liggghts' does not exist") != std::string::npos ||
              blind.message.find("no system/controlDict") != std::string::npos)
      << blind.message;

  const RunResult shared = run(base / "shared", common);
  ASSERT_EQ(shared.exit_code, 0) << shared.message;
  const RunResult apart = run(base / "runs/apart", own);
  ASSERT_EQ(apart.exit_code, 0) << apart.message;

  // The same run, to the bit
  const auto a = cosim::analysis::readTimeSeries(base / "shared/timeseries.csv");
  const auto b = cosim::analysis::readTimeSeries(base / "runs/apart/timeseries.csv");
  ASSERT_EQ(a.rows(), b.rows());
  for (const char* column : {"particle_count", "precursor_in", "precursor_out", "precursor_held",
                             "precursor_removed", "coated_mass", "pressure_drop"}) {
    for (std::size_t r = 0; r < a.rows(); ++r) {
      const double x = a.at(column)[r], y = b.at(column)[r];
      if (!(std::isnan(x) && std::isnan(y))) ASSERT_EQ(x, y) << column << " row " << r;
    }
  }
  // Their files were on their node: the case, sent at the handshake, and their output there
  const std::string id = cosim::analysis::readJsonFile(base / "runs/apart/summary.json")
                             .at("run_id")
                             .get<std::string>();
  EXPECT_TRUE(fs::exists(base / "node" / id / "fluid/system/controlDict"));
  EXPECT_TRUE(fs::exists(base / "node" / id / "particles/in.liggghts"));
  EXPECT_TRUE(fs::is_directory(base / "node" / id / "fluid/0.02"));
  EXPECT_FALSE(fs::exists(base / "runs/apart/fluid/0.02"));
  // and their checkpoints came back into the run folder
  for (const char* name : {"fluid", "particles"}) {
    const fs::path part = base / "runs/apart/checkpoints/0.01" / name;
    ASSERT_TRUE(fs::is_directory(part)) << part;
    EXPECT_FALSE(fs::is_empty(part)) << part;
  }

  // Resumed from the checkpoint at 0.01 s, the restart sent over the link as well
  fs::copy(base / "runs/apart", base / "runs/cut", fs::copy_options::recursive);
  fs::remove_all(base / "runs/cut/checkpoints/0.02");
  const RunResult resumed = run({}, own, base / "runs/cut");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_EQ(resumed.steps, apart.steps);
  const double coated = apart.totals.at("coating_credited_kg");
  EXPECT_NEAR(resumed.totals.at("coating_credited_kg"), coated, 2e-6 * coated);
  EXPECT_NE(text(base / "runs/cut/cosim.log").find("a folder of its own"), std::string::npos);
  fs::remove_all(base);
}

// As a cluster without a shared filesystem: both solvers in a network namespace of their own,
// reaching the orchestrator only over tcp:// on a private link, encrypted with the run's keys,
// and without the run folder. The run is the one on one machine, to the bit.
TEST(OwnFolder, SolversOnAnotherNetworkOverEncryptedTcpWithoutTheRunFolder) {
  const fs::path base = fs::temp_directory_path() / ("cosim-netns-run-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "runs");
  cosim::test::PrivateLink link(getpid());
  ASSERT_TRUE(link.why.empty()) << link.why;
  const fs::path bin = COSIM_BINARY_DIR;
  ASSERT_EQ(shell((bin / "cosim").string() + " keys " + (base / "orchestrator.key").string() +
                  " > /dev/null"),
            0);
  const std::string endpoint =
      "tcp://" + link.host + ":" + std::to_string(20000 + getpid() % 20000);
  std::vector<std::string> apart = {"coupling.end_time=0.01", "transport.bind=" + endpoint,
                                    "transport.key_file=" + (base / "orchestrator.key").string()};
  for (const char* name : {"fluid", "particles"}) {
    const fs::path real = bin / (std::string(name) == "fluid" ? "cosimFoam" : "cosim-liggghts");
    apart.push_back(
        std::string("participants.") + name + ".command=" +
        hidingWrapper(base / (std::string(name) + ".sh"), base / "runs", real, link.ns).string());
    apart.push_back(std::string("participants.") + name + ".workdir=" + (base / "node").string());
  }
  const RunResult remote = run(base / "runs/apart", apart);
  ASSERT_EQ(remote.exit_code, 0) << remote.message;
  const RunResult here = run(base / "here", {"coupling.end_time=0.01"});
  ASSERT_EQ(here.exit_code, 0) << here.message;

  // Both had folders of their own (the wrapper put them in the other network namespace)
  const std::string log = text(base / "runs/apart/cosim.log");
  EXPECT_NE(log.find("a folder of its own"), std::string::npos) << log;
  const auto a = cosim::analysis::readTimeSeries(base / "here/timeseries.csv");
  const auto b = cosim::analysis::readTimeSeries(base / "runs/apart/timeseries.csv");
  ASSERT_EQ(a.rows(), b.rows());
  for (const char* column :
       {"particle_count", "precursor_in", "precursor_removed", "coated_mass", "pressure_drop"}) {
    for (std::size_t r = 0; r < a.rows(); ++r) {
      const double x = a.at(column)[r], y = b.at(column)[r];
      if (!(std::isnan(x) && std::isnan(y))) ASSERT_EQ(x, y) << column << " row " << r;
    }
  }
  fs::remove_all(base);
}
