// A full disk (issue 15): while the case files are copied into the run folder, and while a run
// records. A small tmpfs is the full disk where mounting is permitted (root); a file size limit
// (RLIMIT_FSIZE, EFBIG) stands in for it everywhere else.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "case_files.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/summary.h"
#include "cosim/analysis/time_series.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kSphere = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere";

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void expectFragments(const std::string& msg, const std::vector<std::string>& fragments) {
  for (const auto& f : fragments)
    EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' missing in: " << msg;
}

std::vector<fs::path> tmpFilesIn(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().extension() == ".tmp") found.push_back(e.path());
  return found;
}

// A 200 KB tmpfs: the full disk. Skips the test where mounting is not permitted.
class FullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cosim-full-disk-" + std::to_string(getpid()));
    fs::create_directories(dir_);
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=200k") != 0) {
      const std::string why = std::strerror(errno);
      fs::remove(dir_);
      GTEST_SKIP() << "cannot mount a small tmpfs as the full disk (" << why
                   << "; needs root): covered by the file size limit tests instead";
    }
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    std::error_code ec;
    fs::remove(dir_, ec);
  }
  fs::path dir_;
  bool mounted_ = false;
};

// A scene whose particles participant has a case folder holding one templated file of
// `size` bytes (`in.held`, as in the issue's report).
fs::path sceneWithCaseFile(const std::string& tag, std::size_t size) {
  const fs::path dir =
      fs::temp_directory_path() / ("cosim-full-scene-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "dem");
  std::string text = "# radius ${d/2}\n";
  while (text.size() < size) text += "# filler line of a long LIGGGHTS script, nothing else\n";
  std::ofstream(dir / "dem" / "in.held") << text;
  std::ofstream(dir / "scenario.yaml") << R"(
name: full-disk
parameters: { d: 1.0e-4 }
participants:
  fluid: { adapter: analytic-fluid, options: { velocity: [0, 0, 0] } }
  particles:
    adapter: free-particles
    files: dem
    options: { particles: [ { id: 1, position: [0, 0, 0], radius: 5.0e-5 } ] }
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 1.0e-3 }
models: { drag: { law: stokes } }
)";
  return dir;
}

// Lowers this process's file size limit (writes beyond it fail with EFBIG instead of raising
// SIGXFSZ) for as long as it lives.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    old_handler_ = ::signal(SIGXFSZ, SIG_IGN);
    rlimit lower = saved_;
    lower.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &lower);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    ::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit saved_{};
  sighandler_t old_handler_{};
};

}  // namespace

// The issue: a 0-byte in.held, no error, then a misleading LIGGGHTS message. Now the run stops
// before any participant starts, naming the file and saying the disk is full; no truncated copy.
TEST_F(FullDisk, CaseFileThatDoesNotFitNamesTheFileAndSaysTheDiskIsFull) {
  const fs::path scene = sceneWithCaseFile("copy", 300 * 1024);
  RunOptions o;
  o.quiet = true;
  o.output = dir_ / "run";
  Coupler c(loadScenario(scene), o);
  const RunResult r = c.run();
  EXPECT_EQ(r.exit_code, 4);  // a resource error (cosim/util/errors.h)
  expectFragments(r.message,
                  {(o.output / "particles" / "in.held").string(), "No space left on device",
                   "the disk is full", (scene / "dem" / "in.held").string()});
  EXPECT_FALSE(fs::exists(o.output / "particles" / "in.held")) << "a truncated copy was left";
  EXPECT_TRUE(tmpFilesIn(o.output).empty());
}

// The issue: a clear error, but no summary.json and .tmp files left behind. Now summary.json
// holds the failure (written over the "running" one the run began with), no .tmp file is left,
// and the rows recorded before the disk filled are kept.
TEST_F(FullDisk, RecordingRunOutOfSpaceStillWritesTheSummaryAndLeavesNoTmpFiles) {
  RunOptions o;
  o.quiet = true;
  o.output = dir_ / "run";
  // A snapshot every step of a long run: the 200 KB fill within a few dozen steps.
  Coupler c(loadScenario(kSphere, {"coupling.end_time=1", "output.interval=1e-4"}), o);
  const RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 4) << r.message;
  expectFragments(r.message, {"No space left on device", "the disk is full"});
  EXPECT_TRUE(tmpFilesIn(o.output).empty()) << tmpFilesIn(o.output).front();
  const analysis::Summary s = analysis::readSummary(o.output / analysis::kSummaryFile);
  EXPECT_EQ(s.status, "failed");
  expectFragments(s.message, {"No space left on device", "the disk is full"});
  EXPECT_EQ(s.steps, static_cast<std::int64_t>(r.steps));
  EXPECT_GT(r.steps, 5u);
  EXPECT_LT(r.steps, 10000u);
  // Every completed step has its row, at 1e-4 s apart (and the step the disk filled in, if its
  // row was written before its snapshot failed).
  const auto ts = analysis::readTimeSeries(o.output / analysis::kTimeSeriesFile);
  EXPECT_TRUE(ts.rows() == r.steps || ts.rows() == r.steps + 1) << ts.rows() << " rows";
  for (std::size_t i = 0; i < ts.rows(); ++i)
    EXPECT_NEAR(ts.at("time")[i], 1e-4 * static_cast<double>(i + 1), 1e-12);
}

// The disk filling while the run goes is said at the first checkpoint at which, at the rate the
// disk has been filling since the start, it would be full before the run's end: with the rate,
// the time it is full and the folder's largest parts, long before the disk is full. (The
// numbers are unit-tested in stability_test.cpp.)
TEST_F(FullDisk, ADiskFillingBeforeTheRunsEndIsSaidWhileThereIsStillRoom) {
  RunOptions o;
  o.quiet = true;
  o.output = dir_ / "run";
  Coupler c(loadScenario(kSphere, {"coupling.end_time=1", "output.interval=1e-4",
                                   "checkpoint.interval=5e-4", "checkpoint.keep=1"}),
            o);
  const RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 4) << r.message;
  const std::string log = readFile(o.output / "cosim.log");
  expectFragments(log, {"warning: the run folder's disk has been filling by",
                        "per simulated second since t = 0 s", "before the run's end at 1 s",
                        "The largest parts of the run folder: ", "particles.h5 "});
  // said once, at the first checkpoint (t = 5e-4 s), before the disk was full
  const auto at = log.find("has been filling by");
  EXPECT_EQ(log.find("has been filling by", at + 1), std::string::npos);
  EXPECT_LT(at, log.find("No space left on device"));
}

// Without a tmpfs: a case file beyond the file size limit fails with EFBIG, named, and no
// truncated copy is left.
TEST(FileSizeLimitTest, CaseFileBeyondTheLimitIsNamedAndNotLeftHalfWritten) {
  const fs::path scene = sceneWithCaseFile("rlimit", 100 * 1024);
  const fs::path to = fs::temp_directory_path() / ("cosim-rlimit-case-" + std::to_string(getpid()));
  fs::remove_all(to);
  std::string message;
  {
    FileSizeLimit limit(64 * 1024);
    try {
      copyCaseFiles(scene / "dem", to, {{"d", 1.0e-4}});
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
  expectFragments(message, {(to / "in.held").string(), "File too large", "ulimit -f",
                            (scene / "dem" / "in.held").string()});
  EXPECT_FALSE(fs::exists(to / "in.held"));
  fs::remove_all(to);
  // Below the limit the same copy works, with the parameter substituted.
  copyCaseFiles(scene / "dem", to, {{"d", 1.0e-4}});
  EXPECT_EQ(readFile(to / "in.held").rfind("# radius 5e-05\n", 0), 0u);
  fs::remove_all(to);
}

// An atomic write that fails keeps the old file and leaves no .tmp behind.
TEST(FileSizeLimitTest, FailedAtomicWriteKeepsTheOldFileAndLeavesNoTmp) {
  const fs::path file = fs::temp_directory_path() / ("cosim-rlimit-" + std::to_string(getpid()));
  analysis::writeFileAtomically(file, "old contents\n");
  std::string message;
  {
    FileSizeLimit limit(16 * 1024);
    try {
      analysis::writeFileAtomically(file, std::string(64 * 1024, 'x'));
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
  expectFragments(message, {file.string() + ".tmp", "File too large"});
  EXPECT_EQ(readFile(file), "old contents\n");
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  fs::remove(file);
}
