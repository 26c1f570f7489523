// End to end, as separate processes: this test process is the orchestrator, the analytic fluid
// and the free-particle adapters run as child processes talking ZeroMQ.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <thread>
#include <zmq.hpp>

#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "cosim/util/cpu_binding.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const fs::path kScenario = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere";

fs::path freshFolder(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("cosim-e2e-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  return p;
}

// Children of this process whose command name starts with `prefix`.
std::vector<pid_t> childrenNamed(const std::string& prefix) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // pid (comm) state ppid ...
    auto close = line.rfind(')');
    auto open = line.find('(');
    if (close == std::string::npos || open == std::string::npos) continue;
    const std::string comm = line.substr(open + 1, close - open - 1);
    std::istringstream rest(line.substr(close + 2));
    char state;
    pid_t ppid;
    rest >> state >> ppid;
    if (ppid == getpid() && state != 'Z' && comm.rfind(prefix, 0) == 0)
      out.push_back(std::stoi(name));
  }
  return out;
}

struct History {
  std::vector<double> t, vz;
};

History runSphere(const std::vector<std::string>& sets, const std::string& tag) {
  Scenario sc = loadScenario(kScenario, sets);
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder(tag);
  Coupler c(std::move(sc), o);
  History h;
  c.on_step = [&](double t, const link::ParticleData& s) {
    h.t.push_back(t);
    h.vz.push_back(s.get(field::velocity)[2]);
  };
  RunResult r = c.run();
  EXPECT_EQ(r.exit_code, 0) << r.message;
  EXPECT_TRUE(fs::exists(r.folder / "particles.h5"));
  EXPECT_TRUE(fs::exists(r.folder / "summary.json"));
  return h;
}

// Independent reference: Stokes drag + buoyancy, particle released at rest.
struct Reference {
  double d = 50e-6, rho_p = 2500, rho_f = 1000, mu = 1e-3, g = 9.81;
  double tau() const { return rho_p * d * d / (18 * mu); }
  double vt() const { return (rho_p - rho_f) * g * d * d / (18 * mu); }
  double vz(double t, double u_up) const { return (u_up - vt()) * (1 - std::exp(-t / tau())); }
};

}  // namespace

TEST(EndToEnd, SphereSettlingInStillFluidFollowsStokesSolution) {
  const auto h = runSphere({}, "still");
  Reference ref;
  ASSERT_EQ(h.t.size(), 50u);
  // History: every coupling step against the analytic curve.
  for (std::size_t i = 0; i < h.t.size(); ++i) {
    EXPECT_NEAR(h.vz[i], ref.vz(h.t[i], 0.0), 1e-9 * ref.vt()) << "t = " << h.t[i];
  }
  // Terminal velocity within 0.1 % (5 ms = 14 tau).
  EXPECT_NEAR(-h.vz.back(), ref.vt(), 1e-3 * ref.vt());
  EXPECT_NEAR(ref.vt(), 2.0437e-3, 1e-6);  // hand value: 1500 * 9.81 * 2.5e-9 / 0.018
}

TEST(EndToEnd, SphereInUpwardFlowReachesFlowMinusTerminalVelocity) {
  const double u_up = 1.0e-3;
  const auto h = runSphere({"u_up=0.001"}, "upflow");
  Reference ref;
  for (std::size_t i = 0; i < h.t.size(); ++i) {
    EXPECT_NEAR(h.vz[i], ref.vz(h.t[i], u_up), 1e-9 * ref.vt()) << "t = " << h.t[i];
  }
  EXPECT_NEAR(h.vz.back(), u_up - ref.vt(), 1e-3 * ref.vt());
}

// coupling.cpus: auto. Bound to CPUs the run computes the same history to the bit, and its log
// says where each process ran (with one CPU: that it was not applied).
// A second bound run in the same process (a bench's next stage, a study's next variant) is laid
// out from the CPUs cosim was given, and an unbound one after it gives them back.
TEST(EndToEnd, BoundToCpusTheRunIsTheSameAndSaysWhere) {
  const std::vector<int> allowed = cosim::util::allowedCpus();
  const auto free = runSphere({"u_up=0.001"}, "cpus-free");
  const auto bound = runSphere({"u_up=0.001", "coupling.cpus=auto"}, "cpus-auto");
  runSphere({"u_up=0.001", "coupling.cpus=auto"}, "cpus-again");
  runSphere({"u_up=0.001"}, "cpus-off");
  EXPECT_EQ(cosim::util::allowedCpus(), allowed) << "an unbound run after a bound one";
  ASSERT_EQ(bound.vz.size(), free.vz.size());
  for (std::size_t i = 0; i < free.vz.size(); ++i) EXPECT_EQ(bound.vz[i], free.vz[i]) << i;
  const std::string expected =
      allowed.size() >= 2
          ? "coupling.cpus auto: orchestrator on CPU " + std::to_string(allowed.front()) +
                ", fluid on " + cosim::util::cpuListText({allowed.begin() + 1, allowed.end()}) +
                ", particles on " + std::to_string(allowed.front())
          : std::string("coupling.cpus auto: not applied");
  for (const char* tag : {"cpus-auto-", "cpus-again-"}) {
    std::ifstream log(fs::temp_directory_path() /
                      ("cosim-e2e-" + std::string(tag) + std::to_string(getpid())) / "cosim.log");
    std::stringstream text;
    text << log.rdbuf();
    EXPECT_NE(text.str().find(expected), std::string::npos) << tag << "\n" << text.str();
  }
}

// coupling.scheme: overlapped. The fluid samples the gas during its step at position +
// velocity dt; in a uniform upflow the gas is the same everywhere, so the history must follow the
// same analytic curve, and no Sample may pass between the intervals after the first one.
TEST(EndToEnd, OverlappedSchemeSamplesDuringTheFluidsStepAndFollowsTheSameSolution) {
  const double u_up = 1.0e-3;
  const auto h = runSphere({"u_up=0.001", "coupling.scheme=overlapped"}, "overlapped");
  Reference ref;
  ASSERT_EQ(h.t.size(), 50u);
  for (std::size_t i = 0; i < h.t.size(); ++i) {
    EXPECT_NEAR(h.vz[i], ref.vz(h.t[i], u_up), 1e-9 * ref.vt()) << "t = " << h.t[i];
  }
  std::ifstream summary(fs::temp_directory_path() /
                        ("cosim-e2e-overlapped-" + std::to_string(getpid())) / "summary.json");
  std::stringstream text;
  text << summary.rdbuf();
  EXPECT_NE(text.str().find("\"fluid_sample_ahead_compute\""), std::string::npos) << text.str();
}

// Runs the sphere scene with `sets` and SIGKILLs the child whose name starts with `victim` once
// 10 ms are simulated; returns the run and how long after the kill it ended.
static std::pair<RunResult, double> runAndKill(const std::vector<std::string>& sets,
                                               const std::string& victim, const std::string& tag) {
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder(tag);
  Coupler c(loadScenario(kScenario, sets), o);
  std::chrono::steady_clock::time_point killed_at;
  bool killed = false;
  c.on_step = [&](double t, const link::ParticleData&) {
    if (!killed && t > 0.01) {
      auto pids = childrenNamed(victim);
      ASSERT_EQ(pids.size(), 1u);
      killed_at = std::chrono::steady_clock::now();
      ::kill(pids[0], SIGKILL);
      killed = true;
    }
  };
  RunResult r = c.run();
  EXPECT_TRUE(killed);
  return {std::move(r),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - killed_at).count()};
}

TEST(EndToEnd, KilledParticipantIsReportedWithinFiveSecondsAndNothingIsLeftBehind) {
  const auto [r, detect] =
      runAndKill({"coupling.end_time=1000", "coupling.dt=1e-4"}, "cosim-free-part", "kill");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_LT(detect, 5.0);
  EXPECT_NE(r.message.find("particles"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("killed by signal 9"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("last lines of"), std::string::npos) << r.message;
  EXPECT_TRUE(childrenNamed("cosim-").empty()) << "participant processes left behind";
  // What was recorded is kept.
  EXPECT_TRUE(fs::exists(r.folder / "particles.h5"));
  EXPECT_TRUE(fs::exists(r.folder / "timeseries.csv"));
  std::ifstream summary(r.folder / "summary.json");
  std::stringstream ss;
  ss << summary.rdbuf();
  EXPECT_NE(ss.str().find("failed"), std::string::npos);
  // Nor is the socket file of the ipc:// endpoint left in /tmp.
  const auto at = ss.str().find("\"run_id\": \"");
  ASSERT_NE(at, std::string::npos);
  const std::string id = ss.str().substr(at + 11, ss.str().find('"', at + 11) - at - 11);
  const fs::path socket =
      fs::temp_directory_path() / ("cosim-" + std::to_string(getuid())) / (id + ".ipc");
  EXPECT_FALSE(fs::exists(socket)) << socket << " left behind";
  // The socket's folder is the user's own and closed to others.
  struct stat st {};
  ASSERT_EQ(::stat(socket.parent_path().c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0700u);
}

// coupling.data_path: peer: the fluid killed while the particles wait on their peer link for it.
// The run still ends within five seconds naming the fluid, nothing is left running, and neither
// socket file stays behind.
TEST(EndToEnd, PeerPathFluidKilledIsReportedAndNothingIsLeftBehind) {
  const auto [r, detect] =
      runAndKill({"coupling.end_time=1000", "coupling.dt=1e-4", "coupling.data_path=peer"},
                 "cosim-analytic", "peer-kill");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_LT(detect, 5.0);
  EXPECT_NE(r.message.find("participant 'fluid'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("killed by signal 9"), std::string::npos) << r.message;
  EXPECT_TRUE(childrenNamed("cosim-").empty()) << "participant processes left behind";
  const auto summary = analysis::readJsonFile(r.folder / "summary.json");
  EXPECT_EQ(summary.at("status"), "failed");
  const fs::path folder = fs::temp_directory_path() / ("cosim-" + std::to_string(getuid()));
  const std::string id = summary.at("run_id").get<std::string>();
  EXPECT_FALSE(fs::exists(folder / (id + ".ipc"))) << "the orchestrator's socket left behind";
  EXPECT_FALSE(fs::exists(folder / (id + "-peer.ipc"))) << "the fluid's peer socket left behind";
}

// A client that is not part of the run floods the orchestrator's socket: the flood is dropped
// with one log line, and a participant killed meanwhile is still reported at once.
TEST(EndToEnd, AFloodFromAStrangerNeitherDelaysCrashDetectionNorFillsTheLog) {
  const std::string ep = "ipc:///tmp/cosim-flood-" + std::to_string(getpid()) + ".ipc";
  Scenario sc = loadScenario(kScenario, {"coupling.end_time=1000", "coupling.dt=1e-4",
                                         "transport.bind=" + ep, "transport.heartbeat_timeout=30"});
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("flood");
  Coupler c(std::move(sc), o);
  std::atomic<bool> stop{false};
  std::thread rogue;
  std::chrono::steady_clock::time_point killed_at;
  bool killed = false;
  c.on_step = [&](double t, const link::ParticleData&) {
    if (!rogue.joinable()) {
      rogue = std::thread([&] {
        zmq::context_t ctx;
        zmq::socket_t s(ctx, zmq::socket_type::dealer);
        s.set(zmq::sockopt::routing_id, "stranger");
        s.set(zmq::sockopt::linger, 0);
        s.connect(ep);
        while (!stop) s.send(zmq::str_buffer("not a cosim message"), zmq::send_flags::dontwait);
      });
    }
    if (!killed && t > 0.02) {
      auto pids = childrenNamed("cosim-free-part");
      ASSERT_EQ(pids.size(), 1u);
      killed_at = std::chrono::steady_clock::now();
      ::kill(pids[0], SIGKILL);
      killed = true;
    }
  };
  RunResult r = c.run();
  const double detect =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - killed_at).count();
  stop = true;
  if (rogue.joinable()) rogue.join();
  ASSERT_TRUE(killed);
  EXPECT_LT(detect, 2.0) << "a dead participant must be noticed through the flood";
  EXPECT_NE(r.message.find("killed by signal 9"), std::string::npos) << r.message;
  EXPECT_LT(fs::file_size(r.folder / "cosim.log"), 20000u)
      << "one line per stranger, not per message";
}

TEST(EndToEnd, UnusedFluidIsNotStarted) {
  // Without models, the scene needs no fluid: only the particle process runs (free fall).
  const fs::path dir = freshFolder("nofluid-scn");
  fs::create_directories(dir);
  std::ofstream(dir / "scenario.yaml") << R"(
name: free-fall
participants:
  fluid: { adapter: analytic-fluid }
  particles:
    adapter: free-particles
    options: { particles: [ { id: 1, position: [0, 0, 0], radius: 1.0e-3 } ] }
coupling: { dt: 1.0e-3, dem_steps: 1, end_time: 0.1 }
)";
  Scenario sc = loadScenario(dir);
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("nofluid");
  Coupler c(std::move(sc), o);
  std::size_t fluid_seen = 0;
  c.on_step = [&](double, const link::ParticleData&) {
    fluid_seen += childrenNamed("cosim-analytic").size();
  };
  RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(fluid_seen, 0u);
  EXPECT_FALSE(fs::exists(r.folder / "fluid.log"));
  // Free fall: z = -g t^2 / 2 exactly.
  EXPECT_NEAR(r.final_state.get(field::position)[2], -0.5 * 9.81 * 0.01, 1e-12);
}

TEST(EndToEnd, MissingExecutableIsAClearError) {
  const fs::path dir = freshFolder("noexe-scn");
  fs::create_directories(dir);
  std::ofstream(dir / "scenario.yaml") << R"(
name: noexe
participants:
  particles: { adapter: my-dem, command: cosim-no-such-adapter }
coupling: { dt: 1.0e-3, end_time: 0.1 }
)";
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("noexe");
  Coupler c(loadScenario(dir), o);
  RunResult r = c.run();
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.message.find("cannot find the executable 'cosim-no-such-adapter'"), std::string::npos)
      << r.message;
}

TEST(EndToEnd, SnapshotAndRowAtTimeTHoldTheCoatingOfEveryStepUpToT) {
  // Two fixed particles in still gas with a uniform precursor field; particle 1 is in the zone,
  // particle 2 is not. Ranz-Marshall at Re = 0: Sh = 2, so k = pi mu d Sh / Sc = 2 pi mu d and
  // each step deposits k Y dt = 2 pi * 1.8e-5 * 1e-3 * 0.01 * 1e-3 = 1.1309734e-12 kg on
  // particle 1 (by hand). The snapshot, the on_step state and the time-series row at step n
  // must hold exactly n steps of it.
  const fs::path dir = freshFolder("coat-at-t-scn");
  fs::create_directories(dir);
  std::ofstream(dir / "scenario.yaml") << R"(
name: coating-at-t
participants:
  fluid:
    adapter: analytic-fluid
    options: { velocity: [0, 0, 0], density: 1.0, viscosity: 1.8e-5, voidage: 1.0,
               precursor_fraction: 0.01, pressure_gradient: none }
  particles:
    adapter: free-particles
    options:
      fixed: true
      particles: [ { id: 1, position: [0, 0, 0], radius: 5.0e-4 },
                   { id: 2, position: [0, 0, 1], radius: 5.0e-4 } ]
coupling: { dt: 1.0e-3, dem_steps: 1, end_time: 0.01 }
constants: { schmidt: 1 }
models:
  mass_transfer: { law: ranz_marshall }
  coating_zone: { shape: box, min: [-1, -1, -1], max: [1, 1, 0.5] }
output: { interval: 2.0e-3 }
)";
  const double per_step = 2 * std::numbers::pi * 1.8e-5 * 1e-3 * 0.01 * 1e-3;
  ASSERT_NEAR(per_step, 1.1309734e-12, 1e-19);
  const double dt = 1e-3;
  // Each value is a sum of up to 10 equal credits: round-off of a few ulp at most (measured:
  // 0 to 2e-16 relative).
  constexpr double kTol = 1e-15;
  double worst = 0.0;
  auto err = [&](double v, double n) {
    const double e = n > 0 ? std::fabs(v / (n * per_step) - 1) : std::fabs(v);
    worst = std::max(worst, e);
    return e;
  };
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("coat-at-t");
  Coupler c(loadScenario(dir), o);
  std::size_t steps_seen = 0;
  c.on_step = [&](double t, const link::ParticleData& s) {
    ++steps_seen;
    const double n = std::round(t / dt);
    const auto& m = s.get(field::coating_mass);
    ASSERT_EQ(s.ids, (std::vector<std::int64_t>{1, 2}));
    err(m[0], n);
    EXPECT_NEAR(m[0], n * per_step, kTol * n * per_step) << "on_step at t = " << t;
    EXPECT_EQ(m[1], 0.0);
  };
  RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(steps_seen, 10u);

  analysis::ParticleFile pf(r.folder / "particles.h5");
  ASSERT_EQ(pf.snapshots().size(), 6u);  // 0, 2, 4, 6, 8, 10 ms
  for (std::size_t i = 0; i < pf.snapshots().size(); ++i) {
    const double t = pf.snapshots()[i].time;
    const double n = std::round(t / dt);
    EXPECT_EQ(n, 2.0 * static_cast<double>(i));
    const auto ids = pf.ids(i);
    const auto m = pf.read(i, field::coating_mass);
    ASSERT_EQ(ids, (std::vector<std::int64_t>{1, 2}));
    err(m[0], n);
    EXPECT_NEAR(m[0], n * per_step, kTol * n * per_step) << "snapshot at t = " << t;
    EXPECT_EQ(m[1], 0.0);
  }

  const auto ts = analysis::readTimeSeries(r.folder / analysis::kTimeSeriesFile);
  ASSERT_EQ(ts.rows(), 11u);  // the initial row and one per step
  const auto& time = ts.at("time");
  const auto& removed = ts.at(analysis::column::precursor_removed);
  const auto& coated = ts.at(analysis::column::coated_mass);
  for (std::size_t row = 0; row < ts.rows(); ++row) {
    const double n = std::round(time[row] / dt);
    EXPECT_EQ(n, static_cast<double>(row));
    err(removed[row], n);
    EXPECT_NEAR(removed[row], n * per_step, kTol * n * per_step) << "row at t = " << time[row];
    EXPECT_EQ(coated[row], removed[row]) << "row at t = " << time[row];
  }
  std::printf("coating at t: worst relative error %.2e against n steps of the hand value\n", worst);
  EXPECT_EQ(r.totals.at("coating_credited_kg"), r.totals.at("precursor_removed_kg"));
  EXPECT_NEAR(r.totals.at("coating_on_particles_kg"), 10 * per_step, kTol * 10 * per_step);
}
