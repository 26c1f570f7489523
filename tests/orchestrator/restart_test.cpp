// Checkpoints and resume, as a user meets them: `cosim run` killed with SIGKILL at a random
// moment, or stopped with Ctrl-C, then `cosim resume`, must leave the same run folder as a run
// that never stopped: the same time series (to the bit, wall times aside), the same particle
// snapshots, the same summary totals. The analytic adapters make the solvers themselves exact.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/curve_keys.h"
#include "cosim/link/peer_link.h"
#include "cosim/util/stop_request.h"
#include "coupler.h"
#include "processes.h"
#include "scenario.h"
#include "tcp_relay.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kCosim = fs::path(COSIM_BIN_DIR) / "cosim";

// Parcels held nearly still by a rising gas, coated in a zone, some of them leaving through the
// bottom: the coating owed at a checkpoint, deletions and snapshots all cross the restart.
const char* kScene = R"(name: restart
participants:
  fluid:
    adapter: analytic-fluid
    options: { velocity: [0, 0, 6.0], density: 1.2, viscosity: 1.8e-5, precursor_fraction: 0.01 }
  particles:
    adapter: free-particles
    options:
      density: 2500
      lattice: { count: [5, 5, 8], origin: [-0.004, -0.004, 0.0], spacing: 0.002, radius: 0.0005 }
      domain_min: [-1, -1, -0.004]
      domain_max: [1, 1, 1]
coupling: { dt: 1.0e-3, dem_steps: 1, end_time: 0.12 }
constants: { cg: 1, gravity: [0, 0, -9.81] }
models:
  drag: { law: schiller_naumann }
  mass_transfer: { law: ranz_marshall }
  coating_zone: { shape: box, min: [-0.01, -0.01, 0.004], max: [0.01, 0.01, 0.012] }
output: { interval: 0.01 }
checkpoint: { interval: 0.02, keep: 2 }
)";

struct Workspace {
  fs::path dir;
  Workspace() {
    dir = fs::temp_directory_path() / ("cosim-restart-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "scene.yaml") << kScene;
  }
  ~Workspace() { fs::remove_all(dir); }
};

// Starts cosim with `args` in `dir`; its output goes to `log`.
ChildProcess start(const Workspace& w, const std::vector<std::string>& args,
                   const std::string& log) {
  std::vector<std::string> argv = {kCosim.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return ChildProcess(argv, w.dir, w.dir / log, {});
}

int finish(ChildProcess& p) {
  for (int i = 0; i < 1200 && p.running(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(p.running()) << "cosim did not end within 60 s";
  return p.exitCode();
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Everything two runs must share: the time series without the wall-clock column, every
// snapshot's fields, the summary's totals.
// Two runs of the scene: `long` to 0.16 s, the reference, and `ext` to its own end (0.12 s),
// the one a test then resumes.
void runLongAndShort(const Workspace& w) {
  auto longer =
      start(w, {"run", "scene.yaml", "-o", "long", "--quiet", "--set", "coupling.end_time=0.16"},
            "long.out");
  ASSERT_EQ(finish(longer), 0) << text(w.dir / "long.out");
  auto first = start(w, {"run", "scene.yaml", "-o", "ext", "--quiet"}, "ext.out");
  ASSERT_EQ(finish(first), 0) << text(w.dir / "ext.out");
}

void expectSameRun(const fs::path& a, const fs::path& b) {
  const auto ta = analysis::readTimeSeries(a / "timeseries.csv");
  const auto tb = analysis::readTimeSeries(b / "timeseries.csv");
  ASSERT_EQ(ta.columns, tb.columns);
  ASSERT_EQ(ta.rows(), tb.rows());
  for (const auto& c : ta.columns) {
    if (c == "wall_seconds") continue;
    const auto& x = ta.at(c);
    const auto& y = tb.at(c);
    for (std::size_t r = 0; r < x.size(); ++r) {
      if (std::isnan(x[r]) && std::isnan(y[r])) continue;
      ASSERT_EQ(x[r], y[r]) << c << " row " << r;
    }
  }
  const analysis::ParticleFile pa(a / "particles.h5"), pb(b / "particles.h5");
  ASSERT_EQ(pa.fields(), pb.fields());
  ASSERT_EQ(pa.snapshots().size(), pb.snapshots().size());
  for (std::size_t s = 0; s < pa.snapshots().size(); ++s) {
    const double t = pa.snapshots()[s].time;
    ASSERT_EQ(t, pb.snapshots()[s].time);
    ASSERT_EQ(pa.ids(s), pb.ids(s)) << "snapshot at " << t;
    for (const auto& name : pa.fields())
      ASSERT_EQ(pa.read(s, name), pb.read(s, name)) << name << " at " << t;
  }
  // The passes through the coating zone: the same file, byte for byte.
  ASSERT_EQ(fs::exists(a / "zone_passes.csv"), fs::exists(b / "zone_passes.csv"));
  if (fs::exists(a / "zone_passes.csv"))
    EXPECT_EQ(text(a / "zone_passes.csv"), text(b / "zone_passes.csv"));
  const auto sa = analysis::readJsonFile(a / "summary.json");
  const auto sb = analysis::readJsonFile(b / "summary.json");
  EXPECT_EQ(sa.at("status"), sb.at("status"));
  EXPECT_EQ(sa.at("steps"), sb.at("steps"));
  EXPECT_EQ(sa.at("headline"), sb.at("headline"));
}

// The process started by `parent` whose command line contains `name` (0 if none).
pid_t childNamed(pid_t parent, const std::string& name) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    long ppid = 0;
    rest >> state >> ppid;
    if (ppid != parent) continue;
    if (text(e.path() / "cmdline").find(name) != std::string::npos) return std::stoi(pid);
  }
  return 0;
}

}  // namespace

// Lines of a file so far (0 while it does not exist): how far a run has recorded.
static int lineCount(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

// Runs `scene` with `sets` into `folder` and asks it to stop once its time series has `rows`
// lines: an interrupted run with a checkpoint at the stop.
static RunResult runStoppedAfter(const fs::path& scene, const std::vector<std::string>& sets,
                                 const fs::path& folder, int rows) {
  util::StopRequest stop;
  std::thread asker([&] {
    for (int i = 0; i < 30000 && lineCount(folder / "timeseries.csv") < rows; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    stop.request();
  });
  RunOptions o;
  o.quiet = true;
  o.output = folder;
  o.stop = &stop;
  RunResult r = Coupler(loadScenario(scene, sets), o).run();
  asker.join();
  return r;
}

TEST(Restart, KilledAtARandomMomentAndResumedIsTheUninterruptedRun) {
  Workspace w;
  auto full = start(w, {"run", "scene.yaml", "-o", "full", "--quiet"}, "full.out");
  ASSERT_EQ(finish(full), 0) << text(w.dir / "full.out");
  // The uninterrupted run kept the newest two checkpoints, the last one at its end time.
  ASSERT_TRUE(fs::exists(w.dir / "full/checkpoints/0.12/orchestrator.json"));
  ASSERT_TRUE(fs::exists(w.dir / "full/checkpoints/0.1/orchestrator.json"));
  ASSERT_FALSE(fs::exists(w.dir / "full/checkpoints/0.08"));

  std::mt19937 rng(std::random_device{}());
  const int after = std::uniform_int_distribution<int>(2, 4)(rng);  // checkpoints 0.04 .. 0.08
  const int extra_ms = std::uniform_int_distribution<int>(0, 20)(rng);
  auto cut = start(w, {"run", "scene.yaml", "-o", "cut", "--quiet"}, "cut.out");
  const fs::path wait_for =
      w.dir / "cut/checkpoints" / analysis::formatShortest(0.02 * after) / "orchestrator.json";
  for (int i = 0; i < 2000 && cut.running() && !fs::exists(wait_for); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  std::this_thread::sleep_for(std::chrono::milliseconds(extra_ms));
  ::kill(cut.pid(), SIGKILL);
  finish(cut);
  SCOPED_TRACE("killed after checkpoint " + std::to_string(0.02 * after) + " s + " +
               std::to_string(extra_ms) + " ms");

  const std::string id = analysis::ParticleFile(w.dir / "cut/particles.h5").runId();
  EXPECT_EQ(id.size(), 8u) << "'" << id << "'";
  auto resumed = start(w, {"resume", "cut", "--quiet"}, "resume.out");
  ASSERT_EQ(finish(resumed), 0) << text(w.dir / "resume.out");
  expectSameRun(w.dir / "full", w.dir / "cut");
  // The resumed run is the same run: one id in particles.h5 and summary.json.
  EXPECT_EQ(analysis::ParticleFile(w.dir / "cut/particles.h5").runId(), id);
  EXPECT_EQ(analysis::readJsonFile(w.dir / "cut/summary.json").at("run_id"), id);
  EXPECT_NE(analysis::readJsonFile(w.dir / "full/summary.json").at("run_id"), id);
}

TEST(Restart, CtrlCStopsWithACheckpointAndSaysHowToResume) {
  Workspace w;
  auto full =
      start(w, {"run", "scene.yaml", "-o", "full", "--quiet", "--set", "checkpoint.interval=0"},
            "full.out");
  ASSERT_EQ(finish(full), 0) << text(w.dir / "full.out");
  EXPECT_FALSE(fs::exists(w.dir / "full/checkpoints")) << "interval 0: no periodic checkpoints";

  auto cut =
      start(w, {"run", "scene.yaml", "-o", "cut", "--quiet", "--set", "checkpoint.interval=0"},
            "cut.out");
  // Ctrl-C once the run has recorded a few steps (a fixed delay is too short on a loaded machine)
  for (int i = 0; i < 60000 && cut.running() && lineCount(w.dir / "cut/timeseries.csv") < 3; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(cut.running()) << "the run ended before it could be interrupted: "
                             << text(w.dir / "cut.out");
  ::kill(cut.pid(), SIGINT);
  EXPECT_EQ(finish(cut), 130) << text(w.dir / "cut.out");
  const auto summary = analysis::readJsonFile(w.dir / "cut/summary.json");
  EXPECT_EQ(summary.at("status"), "interrupted");
  EXPECT_NE(summary.at("message").get<std::string>().find("cosim resume"), std::string::npos);
  ASSERT_TRUE(fs::exists(w.dir / "cut/checkpoints")) << "the final checkpoint";

  auto resumed = start(w, {"resume", "cut", "--quiet"}, "resume.out");
  ASSERT_EQ(finish(resumed), 0) << text(w.dir / "resume.out");
  expectSameRun(w.dir / "full", w.dir / "cut");
}

// The stop request is handed to the run (RunOptions::stop), not read from a global: a program
// that embeds the coupler (here the test) stops a run from another thread as Ctrl-C does, with a
// checkpoint from which the run resumes to the uninterrupted one's records.
TEST(Restart, AStopRequestedByTheCallerEndsTheRunWithACheckpoint) {
  Workspace w;
  const std::vector<std::string> sets = {"checkpoint.interval=0"};
  RunOptions fo;
  fo.quiet = true;
  fo.output = w.dir / "full";
  ASSERT_EQ(Coupler(loadScenario(w.dir / "scene.yaml", sets), fo).run().exit_code, 0);

  // once the run has recorded some steps
  const RunResult cut = runStoppedAfter(w.dir / "scene.yaml", sets, w.dir / "cut", 10);
  EXPECT_EQ(cut.exit_code, 130) << cut.message;
  EXPECT_LT(cut.steps, 120u) << "the run ended before the request";
  EXPECT_NE(cut.message.find("stopped on request"), std::string::npos) << cut.message;
  EXPECT_EQ(analysis::readJsonFile(w.dir / "cut/summary.json").at("status"), "interrupted");
  ASSERT_TRUE(fs::exists(w.dir / "cut/checkpoints")) << "the checkpoint at the stop";

  RunOptions ro;
  ro.quiet = true;
  ro.resume = w.dir / "cut";
  ASSERT_EQ(Coupler(loadRunScene(w.dir / "cut"), ro).run().exit_code, 0);
  expectSameRun(w.dir / "full", w.dir / "cut");
}

TEST(Restart, AFinishedRunIsMadeLongerAndEqualsTheLongerRun) {
  Workspace w;
  runLongAndShort(w);
  if (::testing::Test::HasFatalFailure()) return;
  auto again = start(w, {"resume", "ext", "--quiet"}, "again.out");
  EXPECT_EQ(finish(again), 1);  // an input error: nothing left to run
  EXPECT_NE(text(w.dir / "again.out").find("coupling.end_time=..."), std::string::npos)
      << text(w.dir / "again.out");
  auto extend =
      start(w, {"resume", "ext", "--quiet", "--set", "coupling.end_time=0.16"}, "extend.out");
  ASSERT_EQ(finish(extend), 0) << text(w.dir / "extend.out");
  expectSameRun(w.dir / "long", w.dir / "ext");
}

// A finished run whose end lies off the grid of its snapshots (0.125 s, every 0.01 s) made longer:
// its snapshots go on on the grid (0.13, 0.14, ...), not 0.01 s after the end's (0.135, ...); the
// end's own snapshot goes as the records are cut back to the checkpoint, as the longer run has
// none.
TEST(Restart, AFinishedRunOffTheSnapshotGridIsMadeLongerOnTheGrid) {
  Workspace w;
  auto first = start(
      w, {"run", "scene.yaml", "-o", "r", "--quiet", "--set", "coupling.end_time=0.125"}, "r.out");
  ASSERT_EQ(finish(first), 0) << text(w.dir / "r.out");
  auto longer =
      start(w, {"resume", "r", "--quiet", "--set", "coupling.end_time=0.16"}, "longer.out");
  ASSERT_EQ(finish(longer), 0) << text(w.dir / "longer.out");
  std::vector<double> after;
  const analysis::ParticleFile pf(w.dir / "r/particles.h5");
  for (const auto& snap : pf.snapshots())
    if (snap.time > 0.1) after.push_back(snap.time);
  EXPECT_EQ(after, (std::vector<double>{0.11, 0.12, 0.13, 0.14, 0.15, 0.16}));
}

// A run folder moved elsewhere (scratch to project space, another node's disk, a renamed
// study) resumes in its new place: nothing in it points back to where it was run.
TEST(Restart, AMovedRunFolderResumesWhereItNowIs) {
  Workspace w;
  runLongAndShort(w);
  if (::testing::Test::HasFatalFailure()) return;
  fs::create_directories(w.dir / "elsewhere");
  fs::rename(w.dir / "ext", w.dir / "elsewhere" / "moved");
  auto extend = start(
      w, {"resume", "elsewhere/moved", "--quiet", "--set", "coupling.end_time=0.16"}, "moved.out");
  ASSERT_EQ(finish(extend), 0) << text(w.dir / "moved.out");
  EXPECT_FALSE(fs::exists(w.dir / "ext")) << "the resume wrote where the folder used to be";
  expectSameRun(w.dir / "long", w.dir / "elsewhere" / "moved");
}

// The newest checkpoint damaged (its particle state emptied, as a failing disk or a careless
// hand would leave it): the resume fails before its first step and names the other checkpoints
// and the command; `resume --from` the older one sets the damaged one aside (kept) and gives the
// uninterrupted run.
TEST(Restart, ADamagedNewestCheckpointIsNamedAndAnOlderOneContinuesTheRun) {
  Workspace w;
  runLongAndShort(w);
  if (::testing::Test::HasFatalFailure()) return;
  const fs::path newest = w.dir / "ext/checkpoints/0.12";
  ASSERT_TRUE(fs::is_directory(newest));
  for (const auto& f : fs::directory_iterator(newest / "particles"))
    std::ofstream(f.path(), std::ios::trunc);

  auto failed =
      start(w, {"resume", "ext", "--quiet", "--set", "coupling.end_time=0.16"}, "failed.out");
  EXPECT_EQ(finish(failed), 2);
  const std::string out = text(w.dir / "failed.out");
  EXPECT_NE(
      out.find("the resume from the checkpoint at t = 0.12 s failed before it completed a step"),
      std::string::npos)
      << out;
  EXPECT_NE(out.find("other complete checkpoints: 0.1 s"), std::string::npos) << out;
  EXPECT_NE(out.find("cosim resume " + (w.dir / "ext").string() + " --from 0.1"), std::string::npos)
      << out;

  auto none = start(w, {"resume", "ext", "--quiet", "--from", "0.05"}, "none.out");
  EXPECT_EQ(finish(none), 1);  // an input error: no checkpoint at that time
  EXPECT_NE(text(w.dir / "none.out")
                .find("no complete checkpoint at that time; it holds: 0.1 s, "
                      "0.12 s"),
            std::string::npos)
      << text(w.dir / "none.out");

  auto older =
      start(w, {"resume", "ext", "--quiet", "--from", "0.1", "--set", "coupling.end_time=0.16"},
            "older.out");
  ASSERT_EQ(finish(older), 0) << text(w.dir / "older.out");
  EXPECT_TRUE(fs::is_directory(w.dir / "ext/checkpoints/superseded/0.12/particles"));
  expectSameRun(w.dir / "long", w.dir / "ext");
}

TEST(Restart, AChangeTheStateCannotHonourIsRefusedWithWhatDiffers) {
  Workspace w;
  auto run = start(
      w, {"run", "scene.yaml", "-o", "r", "--quiet", "--set", "coupling.end_time=0.04"}, "r.out");
  ASSERT_EQ(finish(run), 0) << text(w.dir / "r.out");
  auto changed =
      start(w,
            {"resume", "r", "--quiet", "--set", "coupling.end_time=0.08", "--set",
             "models.drag.law=stokes", "--set", "constants.cg=2", "--set", "coupling.cpus=auto"},
            "changed.out");
  EXPECT_EQ(finish(changed), 1);  // an input error: the scene changed
  const std::string out = text(w.dir / "changed.out");
  EXPECT_NE(out.find("models.drag.law: schiller_naumann -> stokes"), std::string::npos) << out;
  EXPECT_NE(out.find("constants.cg: 1 -> 2"), std::string::npos) << out;
  EXPECT_EQ(out.find("- coupling.end_time"), std::string::npos) << "end time may change: " << out;
  EXPECT_EQ(out.find("- coupling.cpus"), std::string::npos) << "the binding may change: " << out;
  EXPECT_EQ(analysis::readJsonFile(w.dir / "r/summary.json").at("status"), "completed")
      << "a refused resume leaves the run folder as it was";

  // The same value written another way is no change.
  auto same = start(
      w,
      {"resume", "r", "--quiet", "--set", "coupling.end_time=0.06", "--set", "coupling.dt=0.001"},
      "same.out");
  EXPECT_EQ(finish(same), 0) << text(w.dir / "same.out");

  auto nothing = start(w, {"resume", "r/particles", "--quiet"}, "nothing.out");
  EXPECT_NE(finish(nothing), 0);
  EXPECT_NE(text(w.dir / "nothing.out").find("not a run folder"), std::string::npos)
      << text(w.dir / "nothing.out");
}

// A stiff stretch gets a smaller coupling step from a checkpoint (docs/restarts.md): the steps done
// keep their times, the next ones are the new step long, the step numbers the participants check
// run on, and the DEM step (coupling.dt / coupling.dem_steps) stays what the particle solver's
// restart holds. Run to 0.04 s at 1 ms (2 DEM steps each), resumed to 0.08 s at 0.5 ms (1 DEM
// step).
TEST(Restart, ASmallerCouplingStepFromACheckpointRunsOnTheRunsClock) {
  Workspace w;
  auto run = start(w,
                   {"run", "scene.yaml", "-o", "a", "--quiet", "--set", "coupling.end_time=0.04",
                    "--set", "coupling.dem_steps=2"},
                   "a.out");
  ASSERT_EQ(finish(run), 0) << text(w.dir / "a.out");
  fs::copy(w.dir / "a", w.dir / "b", fs::copy_options::recursive);
  fs::copy(w.dir / "a", w.dir / "c", fs::copy_options::recursive);

  // A new DEM step is refused, naming the dem_steps that keeps it; the folder is left as it was.
  auto dem = start(
      w, {"resume", "a", "--quiet", "--set", "coupling.end_time=0.08", "--set", "coupling.dt=5e-4"},
      "dem.out");
  EXPECT_EQ(finish(dem), 1);
  EXPECT_NE(text(w.dir / "dem.out").find("coupling.dem_steps=1"), std::string::npos)
      << text(w.dir / "dem.out");
  EXPECT_EQ(analysis::readJsonFile(w.dir / "a/summary.json").at("steps"), 40);

  auto finer = start(w,
                     {"resume", "a", "--quiet", "--set", "coupling.end_time=0.08", "--set",
                      "coupling.dt=5e-4", "--set", "coupling.dem_steps=1"},
                     "finer.out");
  ASSERT_EQ(finish(finer), 0) << text(w.dir / "finer.out");
  const auto summary = analysis::readJsonFile(w.dir / "a/summary.json");
  EXPECT_EQ(summary.at("steps"), 40 + 80);
  // A row a step (output.interval 0.01 s records parcels; the series has every step): the 80
  // after 0.04 s are 0.5 ms apart, as written (0.0405, not 0.040499999...)
  const auto ts = analysis::readTimeSeries(w.dir / "a/timeseries.csv");
  std::vector<double> after, expected;
  for (double t : ts.at("time"))
    if (t > 0.04) after.push_back(t);
  for (int k = 1; k <= 80; ++k)
    expected.push_back(std::stod(fmt::format("{:.12g}", 0.04 + k * 5e-4)));
  EXPECT_EQ(after, expected);
  EXPECT_TRUE(fs::exists(w.dir / "a/checkpoints/0.08/orchestrator.json"));
  EXPECT_TRUE(fs::exists(w.dir / "a/checkpoints/0.06/orchestrator.json"));
  // Zone passes after the change begin and end on the half-millisecond steps
  int passes = 0;
  for (const auto& p : analysis::readZonePasses(w.dir / "a/zone_passes.csv")) {
    for (double t : {p.entry_time, p.exit_time}) {
      if (t <= 0.04) continue;
      EXPECT_NEAR(t / 5e-4, std::round(t / 5e-4), 1e-6) << "parcel " << p.parcel_id << " at " << t;
      ++passes;
    }
  }
  EXPECT_GT(passes, 0);
  // The precursor balance closes across the change as across any resume
  const auto& t = summary.at("headline");
  const double in = t.at("precursor_in_kg");
  EXPECT_NEAR(t.at("coating_credited_kg").get<double>(), t.at("precursor_removed_kg").get<double>(),
              1e-12 * in);
  EXPECT_NEAR(in - t.at("precursor_out_kg").get<double>() - t.at("precursor_held_kg").get<double>(),
              t.at("precursor_removed_kg").get<double>(), 1e-9 * in);

  // The clock is in the checkpoint: resumed at 0.5 ms to 0.06 s, then on (the scene of the run
  // keeps the new step) to 0.08 s, the same run to the bit
  auto part = start(w,
                    {"resume", "b", "--quiet", "--set", "coupling.end_time=0.06", "--set",
                     "coupling.dt=5e-4", "--set", "coupling.dem_steps=1"},
                    "part.out");
  ASSERT_EQ(finish(part), 0) << text(w.dir / "part.out");
  auto rest = start(w, {"resume", "b", "--quiet", "--set", "coupling.end_time=0.08"}, "rest.out");
  ASSERT_EQ(finish(rest), 0) << text(w.dir / "rest.out");
  expectSameRun(w.dir / "a", w.dir / "b");

  // A step whose multiples from the start miss the checkpoint's time (0.04 s = 26.7 steps of
  // 1.5 ms): the run goes on, warned that its times leave the grid of the output times
  EXPECT_FALSE(text(w.dir / "finer.out").find("not a whole number") != std::string::npos);
  auto odd = start(w,
                   {"resume", "c", "--quiet", "--set", "coupling.end_time=0.05", "--set",
                    "coupling.dt=1.5e-3", "--set", "coupling.dem_steps=3"},
                   "odd.out");
  ASSERT_EQ(finish(odd), 0) << text(w.dir / "odd.out");
  EXPECT_NE(text(w.dir / "odd.out").find("not a whole number of the new coupling step 0.0015 s"),
            std::string::npos)
      << text(w.dir / "odd.out");
}

// A resume checks that the particles came back exactly as the checkpoint wrote them (a digest of
// every field in orchestrator.json): a participant whose restart lost a field is refused, naming
// it.
TEST(Restart, AParticleStateThatDidNotComeBackExactlyIsRefusedNamingTheField) {
  Workspace w;
  auto run = start(
      w, {"run", "scene.yaml", "-o", "r", "--quiet", "--set", "coupling.end_time=0.04"}, "r.out");
  ASSERT_EQ(finish(run), 0) << text(w.dir / "r.out");
  const fs::path state = w.dir / "r/checkpoints/0.04/orchestrator.json";
  nlohmann::json j = analysis::readJsonFile(state);
  ASSERT_TRUE(j.contains("particle_digest")) << j.dump();
  ASSERT_TRUE(j["particle_digest"].contains("velocity")) << j["particle_digest"].dump();
  // As if the restart had brought the velocities back rounded
  j["particle_digest"]["velocity"] = "0123456789abcdef";
  std::ofstream(state) << j.dump(1);
  auto resumed = start(w, {"resume", "r", "--quiet", "--set", "coupling.end_time=0.06"}, "res.out");
  EXPECT_NE(finish(resumed), 0);
  const std::string out = text(w.dir / "res.out");
  EXPECT_NE(out.find("read back from the checkpoint is not the one written, in: velocity"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("position"), std::string::npos) << "only the velocity differs: " << out;
}

// cosim study continues where it stopped: Ctrl-C during the second variant stops the study (exit
// 130, the variant checkpoints); the same command again reads the first variant back and resumes
// the second from its checkpoint, and both equal an uninterrupted study's variants to the bit.
TEST(Restart, AnInterruptedStudyResumesItsVariantFromTheCheckpoint) {
  Workspace w;
  std::ofstream(w.dir / "scene.yaml", std::ios::app)
      << "observables: { coated: { quantity: totals.coating_on_particles_kg } }\n";
  const std::vector<std::string> study = {"study",
                                          "scene.yaml",
                                          "--vary",
                                          "coupling.dt=1e-3,5e-4",
                                          "--no-plots",
                                          "--set",
                                          "coupling.end_time=0.3",
                                          "--set",
                                          "checkpoint.interval=0.05"};
  auto args = [&](const std::string& out) {
    auto a = study;
    a.insert(a.end(), {"-o", out});
    return a;
  };
  auto whole = start(w, args("whole"), "whole.out");
  ASSERT_EQ(finish(whole), 0) << text(w.dir / "whole.out");

  auto cut = start(w, args("cut"), "cut.out");
  // Ctrl-C once the second variant has recorded a few steps (not after a fixed delay: on a
  // loaded machine the first variant alone can take longer than any delay chosen here)
  for (int i = 0;
       i < 60000 && cut.running() && lineCount(w.dir / "cut/variant-01/timeseries.csv") < 4; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_TRUE(cut.running()) << "the study ended before it could be interrupted: "
                             << text(w.dir / "cut.out");
  ::kill(cut.pid(), SIGINT);
  EXPECT_EQ(finish(cut), 130) << text(w.dir / "cut.out");
  EXPECT_NE(text(w.dir / "cut.out").find("run the same cosim study command again"),
            std::string::npos)
      << text(w.dir / "cut.out");
  EXPECT_EQ(analysis::readJsonFile(w.dir / "cut/variant-01/summary.json").at("status"),
            "interrupted");

  auto again = start(w, args("cut"), "again.out");
  ASSERT_EQ(finish(again), 0) << text(w.dir / "again.out");
  const std::string out = text(w.dir / "again.out");
  EXPECT_NE(out.find("done before"), std::string::npos) << out;
  EXPECT_NE(out.find("resuming"), std::string::npos) << out;
  expectSameRun(w.dir / "whole/variant-00", w.dir / "cut/variant-00");
  expectSameRun(w.dir / "whole/variant-01", w.dir / "cut/variant-01");

  // Made longer: the same study with a later end time resumes each variant from its final
  // checkpoint and equals a study run that long from the start.
  auto longer =
      start(w,
            {"study", "scene.yaml", "--vary", "coupling.dt=1e-3,5e-4", "--no-plots", "--set",
             "coupling.end_time=0.4", "--set", "checkpoint.interval=0.05", "-o", "cut"},
            "longer.out");
  ASSERT_EQ(finish(longer), 0) << text(w.dir / "longer.out");
  EXPECT_NE(text(w.dir / "longer.out").find("resuming"), std::string::npos)
      << text(w.dir / "longer.out");
  auto direct =
      start(w,
            {"study", "scene.yaml", "--vary", "coupling.dt=1e-3,5e-4", "--no-plots", "--set",
             "coupling.end_time=0.4", "--set", "checkpoint.interval=0.05", "-o", "direct"},
            "direct.out");
  ASSERT_EQ(finish(direct), 0) << text(w.dir / "direct.out");
  expectSameRun(w.dir / "direct/variant-01", w.dir / "cut/variant-01");
}

// Any participant killed, not only cosim: the run stops at once naming it (status failed, the
// folder and its checkpoints intact), and `cosim resume` continues from the newest checkpoint to
// the same result, to the bit, as a run that never stopped.
TEST(Restart, EachParticipantKilledAndTheRunResumedIsTheUninterruptedRun) {
  Workspace w;
  auto full =
      start(w, {"run", "scene.yaml", "-o", "full", "--quiet", "--set", "coupling.end_time=0.4"},
            "full.out");
  ASSERT_EQ(finish(full), 0) << text(w.dir / "full.out");
  for (const std::string who : {"cosim-analytic-fluid", "cosim-free-particles"}) {
    SCOPED_TRACE(who);
    const std::string folder = "cut-" + who;
    auto cut =
        start(w, {"run", "scene.yaml", "-o", folder, "--quiet", "--set", "coupling.end_time=0.4"},
              folder + ".out");
    const fs::path wait_for = w.dir / folder / "checkpoints/0.1/orchestrator.json";
    for (int i = 0; i < 5000 && cut.running() && !fs::exists(wait_for); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const pid_t victim = childNamed(cut.pid(), who);
    ASSERT_GT(victim, 0) << "no " << who << " started by cosim";
    ::kill(victim, SIGKILL);
    EXPECT_NE(finish(cut), 0);
    const auto summary = analysis::readJsonFile(w.dir / folder / "summary.json");
    EXPECT_EQ(summary.at("status"), "failed");
    const std::string role = who == "cosim-analytic-fluid" ? "fluid" : "particles";
    EXPECT_NE(summary.at("message").get<std::string>().find(role), std::string::npos)
        << summary.at("message");
    auto resumed = start(w, {"resume", folder, "--quiet"}, folder + "-resume.out");
    ASSERT_EQ(finish(resumed), 0) << text(w.dir / (folder + "-resume.out"));
    expectSameRun(w.dir / "full", w.dir / folder);
  }
}

// Runs started at the same time into the scene's own folder (no -o) never share it: each claims
// its own (same, same-2, ...) and each records a complete run; no lock is left behind.
TEST(RunFolder, RunsStartedTogetherWithTheSameFolderEachGetTheirOwn) {
  Workspace w;
  std::vector<ChildProcess> runs;
  for (int i = 0; i < 5; ++i) {
    runs.push_back(start(w,
                         {"run", "scene.yaml", "--quiet", "--set", "checkpoint.interval=0", "--set",
                          "output.folder=same"},
                         "same" + std::to_string(i) + ".out"));
  }
  for (auto& r : runs) EXPECT_EQ(finish(r), 0);
  const auto one = analysis::readTimeSeries(w.dir / "same/timeseries.csv");
  for (const std::string f : {"same", "same-2", "same-3", "same-4", "same-5"}) {
    SCOPED_TRACE(f);
    ASSERT_TRUE(fs::exists(w.dir / f / "summary.json"));
    EXPECT_EQ(analysis::readJsonFile(w.dir / f / "summary.json").at("status"), "completed");
    EXPECT_EQ(analysis::readTimeSeries(w.dir / f / "timeseries.csv").rows(), one.rows());
    EXPECT_FALSE(fs::exists(w.dir / f / ".cosim-run.lock"));
  }
  EXPECT_FALSE(fs::exists(w.dir / "same-6"));
}

// A folder named with -o is that run's or none: runs started together with the same -o give
// one complete run there and refusals for the others, never a "-2" nobody would look in.
TEST(RunFolder, RunsStartedTogetherWithTheSameOutputOneRunsTheOthersAreRefused) {
  Workspace w;
  std::vector<ChildProcess> runs;
  for (int i = 0; i < 4; ++i) {
    runs.push_back(
        start(w, {"run", "scene.yaml", "-o", "same", "--quiet", "--set", "checkpoint.interval=0"},
              "same" + std::to_string(i) + ".out"));
  }
  int ran = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int code = finish(runs[i]);
    const std::string out = text(w.dir / ("same" + std::to_string(i) + ".out"));
    if (code == 0) {
      ++ran;
      continue;
    }
    EXPECT_EQ(code, 1) << out;
    EXPECT_NE(out.find((w.dir / "same").string()), std::string::npos) << out;
    EXPECT_NE(out.find("choose another folder with -o"), std::string::npos) << out;
  }
  EXPECT_EQ(ran, 1);
  EXPECT_EQ(analysis::readJsonFile(w.dir / "same/summary.json").at("status"), "completed");
  EXPECT_FALSE(fs::exists(w.dir / "same/.cosim-run.lock"));
  EXPECT_FALSE(fs::exists(w.dir / "same-2"));
}

// --overwrite never writes a run over the scene it runs: not into the scenario's own folder,
// not where a participant's folder would land on (or in) a files: folder.
TEST(RunFolder, ARunIsNeverRecordedOverItsScene) {
  Workspace w;
  fs::create_directories(w.dir / "dem");
  std::ofstream(w.dir / "dem" / "note.txt") << "the scene's own file\n";
  const std::string scene = text(w.dir / "scene.yaml");
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"-o", "."}, "is the scene's own folder"},
      {{"-o", "dem/.."}, "is the scene's own folder"},
      {{"-o", "dem", "--set", "participants.particles.files=dem"}, "over the scene's"},
      {{"-o", "dem/sub", "--set", "participants.particles.files=dem"}, "over the scene's"},
  };
  int k = 0;
  for (const auto& c : cases) {
    std::vector<std::string> args = {"run", "scene.yaml", "--quiet", "--overwrite"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const std::string log = "over-scene-" + std::to_string(k++) + ".out";
    auto run = start(w, args, log);
    EXPECT_EQ(finish(run), 1) << text(w.dir / log);
    const std::string out = text(w.dir / log);
    EXPECT_NE(out.find(c.says), std::string::npos) << out;
    EXPECT_NE(out.find("choose another folder with -o"), std::string::npos) << out;
  }
  EXPECT_EQ(text(w.dir / "scene.yaml"), scene);
  EXPECT_FALSE(fs::exists(w.dir / "summary.json"));
  EXPECT_FALSE(fs::exists(w.dir / "dem" / "particles"));
  EXPECT_FALSE(fs::exists(w.dir / "dem" / "summary.json"));
  EXPECT_EQ(text(w.dir / "dem" / "note.txt"), "the scene's own file\n");
}

// A run folder that cannot be made (under a file, on a read-only or missing mount) is named
// with the system's reason, not as a bare filesystem error.
TEST(RunFolder, AFolderThatCannotBeMadeIsNamedWithWhy) {
  Workspace w;
  std::ofstream(w.dir / "plain") << "a file\n";
  auto run = start(w, {"run", "scene.yaml", "--quiet", "-o", "plain/run"}, "unmade.out");
  EXPECT_EQ(finish(run), 1);
  const std::string out = text(w.dir / "unmade.out");
  EXPECT_NE(out.find("cannot create the run folder " + (w.dir / "plain/run").string() +
                     ": Not a directory"),
            std::string::npos)
      << out;
  EXPECT_EQ(text(w.dir / "plain"), "a file\n");
}

TEST(RunFolder, AnExistingOutputFolderIsRefusedWithWhatToDo) {
  Workspace w;
  auto first =
      start(w, {"run", "scene.yaml", "-o", "r", "--quiet", "--set", "coupling.end_time=0.04"},
            "first.out");
  ASSERT_EQ(finish(first), 0) << text(w.dir / "first.out");
  const std::string before = text(w.dir / "r/timeseries.csv");
  const auto summary = analysis::readJsonFile(w.dir / "r/summary.json");

  auto again = start(w, {"run", "scene.yaml", "-o", "r", "--quiet"}, "again.out");
  EXPECT_EQ(finish(again), 1);
  const std::string out = text(w.dir / "again.out");
  const std::string folder = (w.dir / "r").string();
  // Which folder, that it exists, what it holds, and each way out.
  EXPECT_NE(out.find("the run folder " + folder + " already exists"), std::string::npos) << out;
  EXPECT_NE(out.find("completed run of 'restart'"), std::string::npos) << out;
  EXPECT_NE(out.find("choose another folder with -o"), std::string::npos) << out;
  EXPECT_NE(out.find("rm -r " + folder), std::string::npos) << out;
  EXPECT_NE(out.find("--overwrite"), std::string::npos) << out;
  EXPECT_NE(out.find("checkpoint at t = 0.04 s"), std::string::npos) << out;
  EXPECT_NE(out.find("cosim resume " + folder), std::string::npos) << out;
  // Nothing written: not into r, and no r-2 elsewhere.
  EXPECT_EQ(text(w.dir / "r/timeseries.csv"), before);
  EXPECT_EQ(analysis::readJsonFile(w.dir / "r/summary.json"), summary);
  EXPECT_FALSE(fs::exists(w.dir / "r-2"));

  // An empty folder (mkdir, mktemp -d) is fine, and --overwrite writes into a used one.
  fs::create_directories(w.dir / "empty");
  auto empty =
      start(w, {"run", "scene.yaml", "-o", "empty", "--quiet", "--set", "coupling.end_time=0.02"},
            "empty.out");
  EXPECT_EQ(finish(empty), 0) << text(w.dir / "empty.out");
  EXPECT_TRUE(fs::exists(w.dir / "empty/summary.json"));
  auto over = start(
      w,
      {"run", "scene.yaml", "-o", "r", "--quiet", "--overwrite", "--set", "coupling.end_time=0.02"},
      "over.out");
  EXPECT_EQ(finish(over), 0) << text(w.dir / "over.out");
  EXPECT_EQ(analysis::readJsonFile(w.dir / "r/summary.json").at("end_time_s"), 0.02);

  // A file in the way is named as such.
  std::ofstream(w.dir / "afile") << "x";
  auto file = start(w, {"run", "scene.yaml", "-o", "afile", "--quiet"}, "file.out");
  EXPECT_EQ(finish(file), 1);
  EXPECT_NE(text(w.dir / "file.out").find("exists and is not a folder"), std::string::npos)
      << text(w.dir / "file.out");
}

// cosim pack (docs/restarts.md, "Moving a run"): a copy of the stopped run, resumed where it now
// is, gives the run that never stopped; the run folder itself is left as it was.
TEST(Pack, APackedRunResumesElsewhereAsTheUninterruptedRun) {
  Workspace w;
  runLongAndShort(w);
  if (::testing::Test::HasFatalFailure()) return;
  const std::string before = text(w.dir / "ext" / "timeseries.csv");
  auto pack = start(w, {"pack", "ext", "elsewhere/packed/"}, "pack.out");  // a trailing /
  ASSERT_EQ(finish(pack), 0) << text(w.dir / "pack.out");
  const std::string out = text(w.dir / "pack.out");
  EXPECT_NE(out.find("continuing from the checkpoint at t = 0.12 s"), std::string::npos) << out;
  EXPECT_NE(out.find("left out older checkpoints"), std::string::npos) << out;
  EXPECT_NE(out.find("cosim resume elsewhere/packed"), std::string::npos) << out;
  // only the newest checkpoint goes along (keep: 2 leaves 0.1 and 0.12 in the run)
  EXPECT_TRUE(fs::exists(w.dir / "elsewhere/packed/checkpoints/0.12/orchestrator.json"));
  EXPECT_FALSE(fs::exists(w.dir / "elsewhere/packed/checkpoints/0.1"));
  EXPECT_FALSE(fs::exists(w.dir / "elsewhere/packed/.cosim-run.lock"));
  EXPECT_TRUE(fs::exists(w.dir / "ext/checkpoints/0.1")) << "the run folder was changed";
  EXPECT_EQ(text(w.dir / "ext" / "timeseries.csv"), before);
  auto extend = start(
      w, {"resume", "elsewhere/packed", "--quiet", "--set", "coupling.end_time=0.16"}, "r.out");
  ASSERT_EQ(finish(extend), 0) << text(w.dir / "r.out");
  expectSameRun(w.dir / "long", w.dir / "elsewhere" / "packed");
}

// What pack refuses, each with what to do, and nothing written: a destination that exists, one
// inside the run, a folder that is not a run, a run without a checkpoint, a run still going.
TEST(Pack, RefusalsNameTheReasonAndWriteNothing) {
  Workspace w;
  auto first = start(w, {"run", "scene.yaml", "-o", "ext", "--quiet"}, "ext.out");
  ASSERT_EQ(finish(first), 0) << text(w.dir / "ext.out");
  fs::create_directories(w.dir / "full");
  std::ofstream(w.dir / "full" / "keep.txt") << "mine\n";
  auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
    auto p = start(w, args, "refused.out");
    EXPECT_EQ(finish(p), 1);
    const std::string out = text(w.dir / "refused.out");
    EXPECT_NE(out.find(says), std::string::npos) << out;
  };
  refused({"pack", "ext", "full"}, "full already exists and is not an empty folder");
  EXPECT_EQ(text(w.dir / "full" / "keep.txt"), "mine\n");
  refused({"pack", "ext", "ext/inside"}, "lies inside the run folder");
  EXPECT_FALSE(fs::exists(w.dir / "ext" / "inside"));
  refused({"pack", "full", "copy"}, "is not a run folder");
  auto plain =
      start(w, {"run", "scene.yaml", "-o", "plain", "--quiet", "--set", "checkpoint.interval=0"},
            "plain.out");
  ASSERT_EQ(finish(plain), 0) << text(w.dir / "plain.out");
  refused({"pack", "plain", "copy"}, "holds no complete checkpoint");
  EXPECT_FALSE(fs::exists(w.dir / "copy"));
  // a run still going (its lock held): a slow one, packed while it runs
  auto slow =
      start(w, {"run", "scene.yaml", "-o", "slow", "--quiet", "--set", "coupling.end_time=1e3"},
            "slow.out");
  const auto written = [&] {
    std::error_code ec;
    return !fs::is_empty(w.dir / "slow/checkpoints", ec) && !ec;
  };
  for (int i = 0; i < 400 && !written(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  refused({"pack", "slow", "copy"}, "is writing into slow now: stop it first");
  EXPECT_FALSE(fs::exists(w.dir / "copy"));
  ::kill(slow.pid(), SIGKILL);
  finish(slow);
  for (const auto& e : fs::directory_iterator(w.dir))
    EXPECT_EQ(e.path().filename().string().rfind(".partial-", 0), std::string::npos)
        << "a partial copy was left: " << e.path();
}

// The process groups of the participants a run started (each its own, child_process.cpp).
std::vector<pid_t> participantGroups(pid_t orchestrator) {
  std::vector<pid_t> groups;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(e.path() / "stat");
    std::string stat;
    std::getline(in, stat);
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 2));
    char state = 0;
    pid_t ppid = 0, pgrp = 0;
    rest >> state >> ppid >> pgrp;
    if (ppid == orchestrator) groups.push_back(pgrp);
  }
  return groups;
}

// A job suspended and continued (SIGSTOP and SIGCONT) goes on: the time the orchestrator did
// not run is nobody's silence, even past the heartbeat timeout and ZeroMQ's 5 s heartbeat; the
// run then stops on Ctrl-C as any run does, resumable. Suspended whole (Slurm's scontrol
// suspend, a paused virtual machine) or the orchestrator alone (Ctrl-Z and fg in a terminal
// stop only the foreground group; the participants run in groups of their own).
// Over tcp:// (across nodes) only the whole job: a link ZeroMQ's heartbeat finds silent for 5 s
// is taken for cut there, as a stopped orchestrator's is (docs/cluster.md).
enum class Stopped { orchestrator_alone, whole, whole_over_tcp };
class Suspend : public ::testing::TestWithParam<Stopped> {};

TEST_P(Suspend, ARunStoppedLongerThanTheHeartbeatTimeoutsGoesOnWhenContinued) {
  Workspace w;
  std::vector<std::string> args = {"run",
                                   "scene.yaml",
                                   "-o",
                                   "susp",
                                   "--quiet",
                                   "--set",
                                   "coupling.end_time=1e3",
                                   "--set",
                                   "transport.heartbeat_timeout=1"};
  if (GetParam() == Stopped::whole_over_tcp) {
    const fs::path key_file = w.dir / "run.key";
    link::writeKeyPairFile(key_file, link::newCurveKeyPair());
    for (const std::string& a :
         {std::string("--set"),
          "transport.bind=tcp://127.0.0.1:" + std::to_string(test::freeLoopbackPort()),
          std::string("--set"), "transport.key_file=" + key_file.string()})
      args.push_back(a);
  }
  auto run = start(w, args, "susp.out");
  const auto stepping = [&] {
    std::ifstream in(w.dir / "susp" / "timeseries.csv");
    std::string line;
    int n = 0;
    while (std::getline(in, line)) ++n;
    return n > 5;
  };
  for (int i = 0; i < 400 && !stepping(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(stepping()) << text(w.dir / "susp.out");
  const bool whole = GetParam() != Stopped::orchestrator_alone;
  const std::vector<pid_t> groups = whole ? participantGroups(run.pid()) : std::vector<pid_t>{};
  if (whole) ASSERT_EQ(groups.size(), 2U) << "the fluid's and the particles' groups";
  ::kill(run.pid(), SIGSTOP);
  for (const pid_t g : groups) ::kill(-g, SIGSTOP);
  // 7 heartbeat timeouts, and longer than ZeroMQ's 5 s heartbeat on the links
  std::this_thread::sleep_for(std::chrono::milliseconds(7000));
  for (const pid_t g : groups) ::kill(-g, SIGCONT);
  ::kill(run.pid(), SIGCONT);
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  ASSERT_TRUE(run.running()) << text(w.dir / "susp.out");
  const auto steps_then = [&] {
    std::ifstream in(w.dir / "susp" / "timeseries.csv");
    std::string line;
    int n = 0;
    while (std::getline(in, line)) ++n;
    return n;
  };
  const int before = steps_then();
  for (int i = 0; i < 200 && steps_then() <= before; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_GT(steps_then(), before) << "the run does not step after it was continued";
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(finish(run), 130) << text(w.dir / "susp.out");
  EXPECT_NE(text(w.dir / "susp" / "cosim.log").find("did not listen for"), std::string::npos)
      << text(w.dir / "susp" / "cosim.log");
}

INSTANTIATE_TEST_SUITE_P(Stopped, Suspend,
                         ::testing::Values(Stopped::orchestrator_alone, Stopped::whole,
                                           Stopped::whole_over_tcp),
                         [](const auto& info) {
                           return info.param == Stopped::orchestrator_alone ? "TheOrchestratorAlone"
                                  : info.param == Stopped::whole            ? "Whole"
                                                                            : "WholeOverTcp";
                         });

// coupling.data_path: peer (docs/design.md section 5): the particles sample the gas from the fluid,
// evaluate the laws over their parcels and keep the coating ledger and the zone passes of their
// parcels; the orchestrator sends only the schedule and keeps the totals. The scene above (drag,
// coating in a zone, parcels leaving) must give the central path's run bit for bit: the time
// series, every snapshot, the zone passes, the totals.
TEST(PeerPath, GivesTheCentralRunBitForBit) {
  Workspace w;
  const std::vector<std::string> central = {"checkpoint.interval=0"};
  const std::vector<std::string> peer = {"checkpoint.interval=0", "coupling.data_path=peer"};
  RunOptions co;
  co.quiet = true;
  co.output = w.dir / "central";
  ASSERT_EQ(Coupler(loadScenario(w.dir / "scene.yaml", central), co).run().exit_code, 0);
  RunOptions po;
  po.quiet = true;
  po.output = w.dir / "peer";
  const RunResult r = Coupler(loadScenario(w.dir / "scene.yaml", peer), po).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  // The comparison means something: parcels were coated, passed the zone and left
  EXPECT_GT(r.totals.at("coating_credited_kg"), 0.0);
  EXPECT_GT(r.totals.at("particles_deleted"), 0.0);
  EXPECT_GT(lineCount(w.dir / "peer/zone_passes.csv"), 10);
  EXPECT_NEAR(r.totals.at("coating_credited_kg"), r.totals.at("precursor_removed_kg"),
              1e-12 * r.totals.at("precursor_removed_kg"));
  expectSameRun(w.dir / "central", w.dir / "peer");
  // and the per-parcel work was the particles': their sampling and laws are in the timings
  const auto timings = analysis::readJsonFile(w.dir / "peer/summary.json").at("timings_s");
  EXPECT_TRUE(timings.contains("particles_models_compute")) << timings.dump();
}

// A peer run stopped and resumed continues as the central run that never stopped.
TEST(PeerPath, StoppedAndResumedIsTheUninterruptedCentralRun) {
  Workspace w;
  RunOptions fo;
  fo.quiet = true;
  fo.output = w.dir / "full";
  ASSERT_EQ(
      Coupler(loadScenario(w.dir / "scene.yaml", {"checkpoint.interval=0"}), fo).run().exit_code,
      0);
  const RunResult cut =
      runStoppedAfter(w.dir / "scene.yaml", {"checkpoint.interval=0", "coupling.data_path=peer"},
                      w.dir / "cut", 40);
  ASSERT_EQ(cut.exit_code, 130) << cut.message;
  EXPECT_LT(cut.steps, 120u) << "the run ended before the request";
  RunOptions ro;
  ro.quiet = true;
  ro.resume = w.dir / "cut";
  const RunResult resumed = Coupler(loadRunScene(w.dir / "cut"), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  expectSameRun(w.dir / "full", w.dir / "cut");
}

// The particles' part of a peer run's checkpoint holds their coating ledger and open zone passes
// (peer_ledger.pb); a checkpoint without it (an older cosim's, whose orchestrator kept them) is
// refused with that reason, and the run folder keeps what it had.
TEST(PeerPath, AResumeWithoutTheParticlesLedgerIsRefusedWithTheReason) {
  Workspace w;
  const RunResult cut =
      runStoppedAfter(w.dir / "scene.yaml", {"checkpoint.interval=0", "coupling.data_path=peer"},
                      w.dir / "cut", 40);
  ASSERT_EQ(cut.exit_code, 130) << cut.message;
  std::vector<fs::path> parts;
  for (const auto& e : fs::recursive_directory_iterator(w.dir / "cut" / "checkpoints"))
    if (e.path().filename() == link::kPeerLedgerFile) parts.push_back(e.path());
  ASSERT_EQ(parts.size(), 1u) << "one checkpoint, one particle part with the ledger";
  fs::remove(parts[0]);
  const std::string series = text(w.dir / "cut" / "timeseries.csv");
  RunOptions ro;
  ro.quiet = true;
  ro.resume = w.dir / "cut";
  const RunResult refused = Coupler(loadRunScene(w.dir / "cut"), ro).run();
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.message.find("holds no peer_ledger.pb"), std::string::npos) << refused.message;
  EXPECT_NE(refused.message.find("older cosim"), std::string::npos) << refused.message;
  EXPECT_EQ(text(w.dir / "cut" / "timeseries.csv"), series);
}

// Across nodes: the orchestrator's link over tcp:// with CurveZMQ, the fluid's peer socket on a
// port of its own with a key pair of this run for each side; the same run bit for bit.
TEST(PeerPath, OverTcpWithCurveZmqGivesTheSameRun) {
  Workspace w;
  const fs::path key_file = w.dir / "config" / "orchestrator.key";
  link::writeKeyPairFile(key_file, link::newCurveKeyPair());
  const std::vector<std::string> sets = {"checkpoint.interval=0"};
  RunOptions co;
  co.quiet = true;
  co.output = w.dir / "central";
  ASSERT_EQ(Coupler(loadScenario(w.dir / "scene.yaml", sets), co).run().exit_code, 0);
  RunOptions po;
  po.quiet = true;
  po.output = w.dir / "peer";
  const RunResult r = Coupler(loadScenario(w.dir / "scene.yaml",
                                           {"checkpoint.interval=0", "coupling.data_path=peer",
                                            "transport.bind=tcp://127.0.0.1:" +
                                                std::to_string(test::freeLoopbackPort()),
                                            "transport.key_file=" + key_file.string()}),
                              po)
                          .run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  expectSameRun(w.dir / "central", w.dir / "peer");
  EXPECT_NE(text(w.dir / "peer/cosim.log").find("fluid's peer link at tcp://127."),
            std::string::npos)
      << text(w.dir / "peer/cosim.log");
}

// What the peer path takes off the orchestrator: the bytes through the orchestrator's link (a
// relay in front of its port counts them) against the central path's, for the same run. Between
// two snapshots the particles send their ids only, the fluid its report only.
TEST(PeerPath, TakesThePerParcelDataOffTheOrchestratorsLink) {
  Workspace w;
  std::map<std::string, std::size_t> bytes;
  for (const std::string path : {"central", "peer"}) {
    const int port = test::freeLoopbackPort();
    test::TcpRelay relay(port);
    RunOptions o;
    o.quiet = true;
    o.output = w.dir / path;
    const RunResult r =
        Coupler(loadScenario(w.dir / "scene.yaml",
                             {"checkpoint.interval=0", "coupling.data_path=" + path,
                              "transport.bind=tcp://127.0.0.1:" + std::to_string(port),
                              "transport.connect=tcp://127.0.0.1:" + std::to_string(relay.port()),
                              "transport.insecure=true"}),
                o)
            .run();
    ASSERT_EQ(r.exit_code, 0) << r.message;
    bytes[path] = relay.total();
  }
  expectSameRun(w.dir / "central", w.dir / "peer");
  std::printf("bytes through the orchestrator's link: central %zu, peer %zu (%.1f %%)\n",
              bytes["central"], bytes["peer"], 100.0 * bytes["peer"] / bytes["central"]);
  // 200 parcels, 120 steps, a snapshot every 10: the central path sends about six per-parcel
  // messages a step, the peer path one of ids a step and one of the state every tenth
  EXPECT_LT(bytes["peer"], bytes["central"] / 4);
}

// The overlapped scheme on the peer path (the fluid samples ahead for the particles): the central
// overlapped run bit for bit, also when stopped and resumed (the particles keep where the gas was
// sampled ahead in their checkpoint part and sample it there again).
TEST(PeerPath, OverlappedIsTheCentralOverlappedRunStoppedOrNot) {
  Workspace w;
  RunOptions fo;
  fo.quiet = true;
  fo.output = w.dir / "central";
  ASSERT_EQ(Coupler(loadScenario(w.dir / "scene.yaml",
                                 {"checkpoint.interval=0", "coupling.scheme=overlapped"}),
                    fo)
                .run()
                .exit_code,
            0);
  const std::vector<std::string> peer = {"checkpoint.interval=0", "coupling.scheme=overlapped",
                                         "coupling.data_path=peer"};
  RunOptions po;
  po.quiet = true;
  po.output = w.dir / "peer";
  const RunResult r = Coupler(loadScenario(w.dir / "scene.yaml", peer), po).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  expectSameRun(w.dir / "central", w.dir / "peer");
  const RunResult cut = runStoppedAfter(w.dir / "scene.yaml", peer, w.dir / "cut", 40);
  ASSERT_EQ(cut.exit_code, 130) << cut.message;
  RunOptions ro;
  ro.quiet = true;
  ro.resume = w.dir / "cut";
  const RunResult resumed = Coupler(loadRunScene(w.dir / "cut"), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  expectSameRun(w.dir / "central", w.dir / "cut");
}
