// A cut network between the orchestrator and its participants, with the real solvers (the
// CI-sized coating bed): the participants run in a network namespace of their own and reach the
// orchestrator over encrypted tcp:// on a private link (private_link.h), which the tests cut in
// the middle of a run by setting its end on this side down. Packets are then lost silently in
// both directions, as when a cable or a switch between two hosts fails; neither side gets an
// error it could act on, so each must notice the silence by itself.
//
// - A lasting cut: the orchestrator stops the run after transport.heartbeat_timeout (10 s)
//   without a heartbeat, naming the participant and the cut network, with the last checkpoint
//   kept; the participant (launch: external, as on another host) stops by itself once ZeroMQ's
//   heartbeat has closed its connection (5 s) and 3 s more have passed, with exit code 3. The
//   run then resumes from its checkpoint.
// - A cut of 1 s, far below either timeout: the run stalls while it lasts, TCP retransmits what
//   was lost once the link is back, and the run ends with the uncut run's result to the bit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/time_series.h"
#include "cosim/util/child_process.h"
#include "coupler.h"
#include "private_link.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const fs::path kScene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
const fs::path kBin = COSIM_BINARY_DIR;
// 100 coupling steps of 1e-4 s, a checkpoint every 20; the cut comes after step 30. The parallel
// scheme, under which a resumed coating bed agrees with the uninterrupted one to round-off
// (docs/restarts.md).
const std::vector<std::string> kShort = {"coupling.end_time=0.01", "checkpoint.interval=0.002",
                                         "coupling.scheme=parallel"};
constexpr int kCutStep = 30;

std::string text(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double seconds(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

bool waitFor(double limit, const std::function<bool()>& done) {
  const auto until = Clock::now() + std::chrono::duration<double>(limit);
  while (Clock::now() < until) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return done();
}

RunResult run(const std::vector<std::string>& sets, const fs::path& out,
              const std::function<void()>& each_step = {}, const fs::path& resume = {}) {
  RunOptions o;
  o.quiet = true;
  if (resume.empty()) o.output = out;
  o.resume = resume;
  Coupler c(loadScenario(kScene, sets), o);
  if (each_step) c.on_step = [&](double, const cosim::link::ParticleData&) { each_step(); };
  return c.run();
}

// The run both tests compare with: the same scene on this host over ipc://, never cut.
struct Reference {
  RunResult result;
  cosim::analysis::TimeSeries series;
};
const Reference& reference() {
  static const Reference ref = [] {
    const fs::path out =
        fs::temp_directory_path() / ("cosim-netcut-reference-" + std::to_string(getpid()));
    fs::remove_all(out);
    Reference r{run(kShort, out), {}};
    if (r.result.exit_code == 0) r.series = cosim::analysis::readTimeSeries(out / "timeseries.csv");
    fs::remove_all(out);
    return r;
  }();
  return ref;
}

// Every column of `b` but the wall time equal to the reference's, to the bit, in the rows with
// time <= until.
void expectSameRows(const cosim::analysis::TimeSeries& b, double until) {
  const auto& a = reference().series;
  ASSERT_EQ(a.columns, b.columns);
  for (const auto& column : a.columns) {
    if (column == "wall_seconds") continue;
    for (std::size_t r = 0; r < std::min(a.rows(), b.rows()) && a.at("time")[r] <= until; ++r) {
      const double x = a.at(column)[r], y = b.at(column)[r];
      if (!(std::isnan(x) && std::isnan(y))) ASSERT_EQ(x, y) << column << " row " << r;
    }
  }
}

// The particles participant of launch: external, started in network namespace `ns` (as on
// another host) with the arguments cosim logs for it (the nth time it logs them: one per start
// or resume); its exit code and when it exited.
class ExternalParticles {
 public:
  ExternalParticles(const fs::path& run, const std::string& ns, const fs::path& log, int nth) {
    thread_ = std::thread([this, run, ns, log, nth] {
      const std::string marker = "waiting for particles (launch: external): start it with ";
      std::vector<std::string> args;
      const bool logged = waitFor(60, [&] {
        const std::string t = text(run / "cosim.log");
        std::size_t at = std::string::npos;
        for (int i = 0; i < nth; ++i) {
          at = t.find(marker, at == std::string::npos ? 0 : at + 1);
          if (at == std::string::npos) return false;
        }
        const auto end = t.find('\n', at);
        if (end == std::string::npos) return false;
        std::istringstream line(t.substr(at + marker.size(), end - at - marker.size()));
        for (std::string a; line >> a;) args.push_back(a);
        return true;
      });
      if (!logged) return;
      std::vector<std::string> argv = {"ip", "netns", "exec", ns,
                                       (kBin / "cosim-liggghts").string()};
      argv.insert(argv.end(), args.begin(), args.end());
      cosim::util::ChildProcess p(argv, run.parent_path(), log, {});
      code_ = p.wait();
      exited_at_ = Clock::now();
    });
  }
  ~ExternalParticles() { join(); }
  void join() {
    if (thread_.joinable()) thread_.join();
  }
  // After join(): its exit code (-1: never started) and when it exited.
  int code() const { return code_; }
  Clock::time_point exitedAt() const { return exited_at_; }

 private:
  std::thread thread_;
  int code_ = -1;
  Clock::time_point exited_at_;
};

// The scene's link to the namespace: tcp:// on the host's end of the private link (any free
// port), encrypted with a key pair made for the test.
std::vector<std::string> overTheLink(const cosim::test::PrivateLink& link, const fs::path& base) {
  const fs::path key = base / "orchestrator.key";
  if (!fs::exists(key))
    std::system(((kBin / "cosim").string() + " keys " + key.string() + " > /dev/null").c_str());
  std::vector<std::string> sets = kShort;
  sets.push_back("transport.bind=tcp://" + link.host + ":*");
  sets.push_back("transport.key_file=" + key.string());
  return sets;
}

}  // namespace

// A cut that lasts: each side notices the silence within its own timeout and stops by itself;
// the run keeps its checkpoint and resumes from it once the network is back.
TEST(NetworkCut, ALastingCutStopsBothSidesEachWithinItsTimeoutAndTheRunResumes) {
  cosim::test::PrivateLink link(getpid() + 1);
  ASSERT_TRUE(link.why.empty()) << link.why;  // never skipped: a machine without namespaces fails
  const fs::path base = fs::temp_directory_path() / ("cosim-netcut-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  ASSERT_EQ(reference().result.exit_code, 0) << reference().result.message;
  std::vector<std::string> sets = overTheLink(link, base);
  sets.push_back("participants.particles.launch=external");

  // The fluid on this host (cosim starts it), the particles on the other side of the link.
  ExternalParticles particles(base / "run", link.ns, base / "particles-1.log", 1);
  int steps = 0;
  Clock::time_point cut_at;
  std::string cut_error = "not cut";
  const RunResult r = run(sets, base / "run", [&] {
    if (++steps != kCutStep) return;
    cut_error = link.cut();
    cut_at = Clock::now();
  });
  const auto failed_at = Clock::now();
  particles.join();
  const std::string restore_error = link.restore();
  ASSERT_EQ(cut_error, "");
  ASSERT_EQ(restore_error, "");
  const double orchestrator_s = seconds(cut_at, failed_at);
  const double participant_s = seconds(cut_at, particles.exitedAt());
  std::printf(
      "cut after step %d: the orchestrator failed the run after %.2f s, the participant "
      "stopped after %.2f s\n",
      kCutStep, orchestrator_s, participant_s);

  // The orchestrator: no reply, no heartbeat from the particles for transport.heartbeat_timeout
  // (10 s; their last heartbeat came at most 0.5 s before the cut), then the run fails naming
  // them, with the checkpoint at 0.002 s to resume from.
  EXPECT_EQ(r.exit_code, 3) << r.message;  // a peer error
  EXPECT_EQ(r.steps, static_cast<std::size_t>(kCutStep));
  EXPECT_GE(orchestrator_s, 9.4);
  EXPECT_LE(orchestrator_s, 12.0);
  EXPECT_NE(r.message.find("participant 'particles': silent for 10 s at step 31: not even a "
                           "heartbeat (transport.heartbeat_timeout 10 s); its process hung, its "
                           "host went down, or the network between it and the orchestrator is "
                           "cut"),
            std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("its newest checkpoint is t = 0.002 s: once the cause is fixed, "
                           "continue with\n  cosim resume " +
                           (base / "run").string()),
            std::string::npos)
      << r.message;
  const auto summary = cosim::analysis::readJsonFile(base / "run/summary.json");
  EXPECT_EQ(summary.at("status"), "failed");
  const std::string said = summary.at("message").get<std::string>();
  EXPECT_EQ(said.rfind("participant 'particles': silent for 10 s", 0), 0u) << said;
  EXPECT_NE(said.find("the network between it and the orchestrator is cut"), std::string::npos);
  EXPECT_TRUE(fs::exists(base / "run/checkpoints/0.002/orchestrator.json"));
  // What was recorded before the cut is the uncut run's
  expectSameRows(cosim::analysis::readTimeSeries(base / "run/timeseries.csv"), 1.0);

  // The participant: ZeroMQ's heartbeat (every 1 s, 5 s timeout) closes its connection, 3 s
  // without one means the orchestrator is gone; it was waiting for a command, so it stops then.
  EXPECT_EQ(particles.code(), 3) << text(base / "particles-1.log");
  EXPECT_GE(participant_s, 7.9);
  EXPECT_LE(participant_s, 12.0);
  const std::string endpoint = "tcp://" + link.host + ":";
  const std::string plog = text(base / "particles-1.log");
  EXPECT_NE(plog.find("[particles] the orchestrator at " + endpoint), std::string::npos) << plog;
  EXPECT_NE(plog.find(" is gone: no connection to it for 3 s (cosim was killed, its host is down, "
                      "or the network to it is cut); stopping"),
            std::string::npos)
      << plog;

  // The network back, the run resumes from its checkpoint (the particles started again on
  // their side) and goes on to 0.005 s: the rows to the checkpoint are the uncut run's, and what
  // follows agrees with it as a resumed coating bed does (docs/restarts.md: to round-off)
  ExternalParticles again(base / "run", link.ns, base / "particles-2.log", 2);
  std::vector<std::string> longer = sets;
  for (auto& s : longer)
    if (s.rfind("coupling.end_time=", 0) == 0) s = "coupling.end_time=0.005";
  const RunResult resumed = run(longer, {}, {}, base / "run");
  again.join();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_EQ(again.code(), 0) << text(base / "particles-2.log");
  EXPECT_EQ(resumed.steps, 50u);
  const auto series = cosim::analysis::readTimeSeries(base / "run/timeseries.csv");
  ASSERT_EQ(series.rows(), 51u);
  expectSameRows(series, 0.002);
  const auto& ref = reference().series;
  // The first step after the resume agrees to round-off (measured: 8.7e-13 relative in the
  // pressure drop, the coating columns exact), the 30 after it to 2.6e-15 in the coated mass
  for (const char* column : {"pressure_drop", "coated_mass", "precursor_removed"}) {
    const double x = ref.at(column)[21];
    EXPECT_NEAR(series.at(column)[21], x, 1e-11 * std::fabs(x)) << column;
  }
  for (std::size_t row = 21; row < series.rows(); ++row) {
    ASSERT_EQ(series.at("time")[row], ref.at("time")[row]);
    EXPECT_EQ(series.at("particle_count")[row], ref.at("particle_count")[row]);
    for (const char* column : {"coated_mass", "precursor_removed"}) {
      const double x = ref.at(column)[row];
      EXPECT_NEAR(series.at(column)[row], x, 1e-14 * x) << column << " row " << row;
    }
  }
  EXPECT_EQ(cosim::analysis::readJsonFile(base / "run/summary.json").at("status"), "completed");
  fs::remove_all(base);
}

// A run with both solvers on the other side of `link`, started by cosim through a wrapper, whose
// link is cut after step kCutStep for `cut` seconds; when each thing happened.
struct CutRun {
  RunResult result;
  std::string cut_error = "not cut", restore_error = "not restored";
  int steps_while_cut = -1;
  Clock::time_point cut_at, restored_at, next_step_at, ended_at;
};
CutRun cutFor(double cut, const cosim::test::PrivateLink& link, const fs::path& base) {
  std::vector<std::string> sets = overTheLink(link, base);
  for (const char* name : {"fluid", "particles"}) {
    const fs::path real = kBin / (std::string(name) == "fluid" ? "cosimFoam" : "cosim-liggghts");
    const fs::path wrapper = base / (std::string(name) + ".sh");
    std::ofstream(wrapper) << "#!/bin/sh\nexec ip netns exec " << link.ns << " " << real.string()
                           << " \"$@\"\n";
    fs::permissions(wrapper, fs::perms::owner_all);
    sets.push_back(std::string("participants.") + name + ".command=" + wrapper.string());
  }
  CutRun c;
  std::atomic<int> steps{0};
  std::thread restorer;
  c.result = run(sets, base / "run", [&] {
    const int k = ++steps;
    if (k == kCutStep) {
      c.cut_error = link.cut();
      c.cut_at = Clock::now();
      restorer = std::thread([&] {
        std::this_thread::sleep_for(std::chrono::duration<double>(cut));
        c.steps_while_cut = steps.load();
        c.restore_error = link.restore();
        c.restored_at = Clock::now();
      });
    } else if (k == kCutStep + 1) {
      c.next_step_at = Clock::now();
    }
  });
  c.ended_at = Clock::now();
  if (restorer.joinable()) restorer.join();
  return c;
}

// A cut of 1 s: the run waits while it lasts and then goes on; nothing is lost, nothing is
// received twice, and the result is the uncut run's to the bit.
TEST(NetworkCut, AOneSecondCutDelaysTheRunAndLeavesItsResultToTheBit) {
  cosim::test::PrivateLink link(getpid() + 2);
  ASSERT_TRUE(link.why.empty()) << link.why;  // never skipped: a machine without namespaces fails
  const fs::path base =
      fs::temp_directory_path() / ("cosim-netcut-short-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const RunResult& uncut = reference().result;
  ASSERT_EQ(uncut.exit_code, 0) << uncut.message;
  const CutRun c = cutFor(1.0, link, base);
  const RunResult& r = c.result;
  ASSERT_EQ(c.cut_error, "");
  ASSERT_EQ(c.restore_error, "");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  const double stall = seconds(c.cut_at, c.next_step_at);
  std::printf(
      "cut for %.2f s after step %d: the next step came %.2f s after the cut, %.2f s "
      "after the link was back\n",
      seconds(c.cut_at, c.restored_at), kCutStep, stall, seconds(c.restored_at, c.next_step_at));

  // The cut did stop the run while it lasted, and TCP's retransmission (its timer doubling from
  // 0.2 s: 0.2, 0.6, 1.4 s after a loss) brought it back soon after the link (measured: the next
  // step 1.5 to 1.7 s after the cut)
  EXPECT_EQ(c.steps_while_cut, kCutStep);
  EXPECT_GE(stall, 1.0);
  EXPECT_LE(stall, 3.5);
  EXPECT_EQ(r.steps, uncut.steps);

  // The uncut run, to the bit: every row, every parcel, every total
  expectSameRows(cosim::analysis::readTimeSeries(base / "run/timeseries.csv"), 1.0);
  EXPECT_EQ(cosim::analysis::readTimeSeries(base / "run/timeseries.csv").rows(),
            reference().series.rows());
  ASSERT_EQ(r.final_state.ids, uncut.final_state.ids);
  ASSERT_EQ(r.final_state.names(), uncut.final_state.names());
  for (const auto& field : uncut.final_state.names())
    EXPECT_EQ(r.final_state.get(field), uncut.final_state.get(field)) << field;
  EXPECT_EQ(r.totals, uncut.totals);
  EXPECT_EQ(cosim::analysis::readJsonFile(base / "run/summary.json").at("status"), "completed");
  fs::remove_all(base);
}

// A cut of 7 s: longer than ZeroMQ's heartbeat (5 s), which closes the connections, shorter than
// the 3 s more after which a participant counts the orchestrator as gone, and than the
// orchestrator's 10 s heartbeat timeout. ZeroMQ connects again once the link is back, but what
// was in flight on the closed connections is lost: each participant stops then (exit code 3)
// saying so, and the orchestrator sees it exit at once. (Before, the run waited for a reply that
// never came until participants.NAME.timeout, 300 s by default, and blamed a slow step.)
TEST(NetworkCut, ACutLongerThanZeroMQsHeartbeatStopsTheRunOnceTheLinkIsBack) {
  cosim::test::PrivateLink link(getpid() + 3);
  ASSERT_TRUE(link.why.empty()) << link.why;  // never skipped: a machine without namespaces fails
  const fs::path base =
      fs::temp_directory_path() / ("cosim-netcut-middle-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const CutRun c = cutFor(7.0, link, base);
  const RunResult& r = c.result;
  ASSERT_EQ(c.cut_error, "");
  ASSERT_EQ(c.restore_error, "");
  const double after_cut = seconds(c.cut_at, c.ended_at);
  std::printf("cut for %.2f s after step %d: the run failed %.2f s after the cut\n",
              seconds(c.cut_at, c.restored_at), kCutStep, after_cut);
  EXPECT_EQ(r.exit_code, 3) << r.message;  // a peer error
  EXPECT_EQ(r.steps, static_cast<std::size_t>(kCutStep));
  EXPECT_GE(after_cut, 7.0);
  EXPECT_LE(after_cut, 12.0);
  // A participant exited with code 3 saying why: connected again (or, had it not connected
  // again within 3 s of losing the connection, the orchestrator gone)
  EXPECT_NE(r.message.find("process (openfoam) exited with code 3 at step 31"), std::string::npos)
      << r.message;
  EXPECT_TRUE(r.message.find("was lost and made again (the network between them was cut for "
                             "longer than ZeroMQ's 5 s heartbeat)") != std::string::npos ||
              r.message.find("is gone: no connection to it for 3 s") != std::string::npos)
      << r.message;
  EXPECT_TRUE(fs::exists(base / "run/checkpoints/0.002/orchestrator.json"));
  fs::remove_all(base);
}
