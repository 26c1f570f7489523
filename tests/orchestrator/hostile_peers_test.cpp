// Hostile and careless peers (issue 15): cosim killed with SIGKILL under its participants, the
// socket files such a run leaves behind, and strangers sending forged Hellos to the
// orchestrator's socket. Analytic adapters as separate processes; cosim itself as a separate
// process where it is killed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "cosim/link/fields.h"
#include "cosim/link/session.h"
#include "cosim/link/transport.h"
#include "cosim/util/child_process.h"
#include "coupler.h"
#include "run_token.h"
#include "scenario.h"
#include "socket_folder.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const fs::path kSphere = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere";

fs::path freshFolder(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("cosim-peers-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  return p;
}

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Waits up to `seconds` for `done`; false on timeout.
template <class F>
bool waitFor(double seconds, F done) {
  const auto t0 = Clock::now();
  while (!done()) {
    if (secondsSince(t0) > seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return true;
}

// A live process (not a zombie) with this pid.
bool alive(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

// Processes whose parent is `parent`.
std::vector<pid_t> childrenOf(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state;
    pid_t ppid;
    rest >> state >> ppid;
    if (ppid == parent && state != 'Z') out.push_back(std::stoi(name));
  }
  return out;
}

// `cosim run` of a scene (the settling sphere) for a long time, as a process of its own.
util::ChildProcess startCosim(const fs::path& out, const std::vector<std::string>& sets,
                              const fs::path& scene = kSphere) {
  std::vector<std::string> argv = {COSIM_EXE,    "run",   scene.string(),          "-o",
                                   out.string(), "--set", "coupling.end_time=1000"};
  for (const auto& s : sets) argv.insert(argv.end(), {"--set", s});
  fs::create_directories(out.parent_path());
  return util::ChildProcess(argv, ".", out.string() + ".out", {});
}

// The arguments cosim prints for starting an external participant.
std::vector<std::string> externalArguments(const fs::path& cosim_out, const std::string& name) {
  std::vector<std::string> args;
  waitFor(10, [&] {
    const std::string text = readFile(cosim_out);
    const std::string marker = "waiting for " + name + " (launch: external): start it with ";
    const auto at = text.find(marker);
    if (at == std::string::npos || text.find('\n', at) == std::string::npos) return false;
    std::istringstream line(
        text.substr(at + marker.size(), text.find('\n', at) - at - marker.size()));
    for (std::string a; line >> a;) args.push_back(a);
    return true;
  });
  return args;
}

std::string argumentAfter(const std::vector<std::string>& args, const std::string& flag) {
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == flag) return args[i + 1];
  return "";
}

// Rows in the run's time series so far.
std::size_t rows(const fs::path& run) {
  const std::string text = readFile(run / "timeseries.csv");
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

// ---- cosim killed with SIGKILL ---------------------------------------------------------------

// An external participant (started by hand, not a child of cosim) notices that the orchestrator
// is gone within seconds and stops with a clear message, instead of waiting out its 600 s
// command timeout. The token it needs is in a file only the user can read, never on a command
// line; a participant cosim starts gets it through its environment.
TEST(KilledOrchestrator, ExternalParticipantStopsWithinSecondsWithAClearMessage) {
  const fs::path run = freshFolder("external") / "run";
  auto cosim = startCosim(run, {"participants.particles.launch=external"});
  const auto args = externalArguments(run.string() + ".out", "particles");
  ASSERT_FALSE(args.empty()) << readFile(run.string() + ".out");
  const fs::path token_file = argumentAfter(args, "--token-file");
  ASSERT_EQ(token_file, run / kRunTokenFile);
  struct stat st {};
  ASSERT_EQ(::stat(token_file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u) << "the token file must be readable by the user only";
  const std::string token = readFile(token_file).substr(0, 32);
  ASSERT_EQ(token.size(), 32u);

  // The fluid, started by cosim: the token in its environment, not in its command line.
  std::vector<pid_t> local;
  ASSERT_TRUE(waitFor(10, [&] { return !(local = childrenOf(cosim.pid())).empty(); }));
  std::string cmdline = readFile("/proc/" + std::to_string(local[0]) + "/cmdline");
  EXPECT_EQ(cmdline.find(token), std::string::npos) << "the token is visible in ps";
  EXPECT_NE(readFile("/proc/" + std::to_string(local[0]) + "/environ")
                .find(std::string(link::kRunTokenVariable) + "=" + token),
            std::string::npos);

  std::vector<std::string> argv = {std::string(COSIM_BIN_DIR) + "/cosim-free-particles"};
  argv.insert(argv.end(), args.begin(), args.end());
  const fs::path plog = run.string() + ".particles.log";
  util::ChildProcess particles(argv, ".", plog, {});
  ASSERT_TRUE(waitFor(20, [&] { return rows(run) > 5; })) << readFile(run.string() + ".out");

  ::kill(cosim.pid(), SIGKILL);
  const auto killed = Clock::now();
  EXPECT_TRUE(waitFor(15, [&] { return !particles.running(); }))
      << "the external participant outlived its orchestrator";
  const double gone = secondsSince(killed);
  std::printf("external participant stopped %.2f s after cosim was killed\n", gone);
  EXPECT_LT(gone, 6.0);
  EXPECT_EQ(particles.exitCode(), 3) << particles.exitDescription();
  const std::string said = readFile(plog);
  EXPECT_NE(said.find("the orchestrator at " + argumentAfter(args, "--endpoint") + " is gone"),
            std::string::npos)
      << said;
  EXPECT_TRUE(waitFor(5, [&] { return !alive(local[0]); })) << "the local fluid outlived cosim";
  cosim.wait();
}

// Participants cosim starts itself die with it (parent-death signal), and the socket file the
// killed run leaves in /tmp/cosim-<uid>/ is removed by the next run once it is provably dead.
TEST(KilledOrchestrator, LocalParticipantsDieWithItAndItsSocketFileIsCleanedUpLater) {
  const fs::path run = freshFolder("local") / "run";
  auto cosim = startCosim(run, {});
  ASSERT_TRUE(waitFor(20, [&] { return rows(run) > 5; })) << readFile(run.string() + ".out");
  const auto local = childrenOf(cosim.pid());
  ASSERT_EQ(local.size(), 2u);
  const std::string log = readFile(run / "cosim.log");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(log, m, std::regex("--endpoint, ipc://([^,]+),"))) << log;
  const fs::path socket = m[1].str();

  ::kill(cosim.pid(), SIGKILL);
  const auto killed = Clock::now();
  EXPECT_TRUE(waitFor(10, [&] { return !alive(local[0]) && !alive(local[1]); }));
  EXPECT_LT(secondsSince(killed), 5.0);
  cosim.wait();

  // The killed run could not remove its socket; nothing listens on it any more.
  ASSERT_EQ(fs::symlink_status(socket).type(), fs::file_type::socket) << socket;
  EXPECT_TRUE(isDeadSocket(socket));
  privateSocketFolder();  // what every run does first: too young to be removed yet
  EXPECT_TRUE(fs::exists(fs::symlink_status(socket)));
  fs::last_write_time(socket, fs::file_time_type::clock::now() - std::chrono::minutes(2));
  privateSocketFolder();
  EXPECT_FALSE(fs::exists(fs::symlink_status(socket))) << socket << " left behind";
}

// A run that is suspended (Ctrl-Z, kill -STOP: its socket accepts nothing, its backlog fills up)
// is alive: a new run's look through the socket folder says so at once instead of waiting for it
// to accept (before, every run started beside a suspended one hung in connect()).
TEST(KilledOrchestrator, ASuspendedRunsSocketIsAliveAndTheLookDoesNotWait) {
  const fs::path path =  // short: a socket's path has room for 107 characters
      fs::temp_directory_path() / ("cosim-suspended-" + std::to_string(getpid()) + ".ipc");
  fs::remove(path);
  const int listener = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(listener, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, path.c_str(), sizeof(addr.sun_path) - 1);
  ASSERT_EQ(::bind(listener, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(listener, 1), 0);  // and never accepts, as a stopped process
  std::vector<int> held;
  for (int i = 0; i < 8; ++i) {  // fill the backlog
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
      ::close(fd);
      break;
    }
    held.push_back(fd);
  }
  const auto t0 = Clock::now();
  EXPECT_FALSE(isDeadSocket(path));
  EXPECT_LT(secondsSince(t0), 1.0) << "the look waited for the suspended run";
  for (const int fd : held) ::close(fd);
  ::close(listener);
  EXPECT_TRUE(isDeadSocket(path)) << "nothing listens any more";
  fs::remove(path);
}

// The same with the real DEM solver: an external cosim-liggghts stops within seconds, and a
// local one under mpirun (2 ranks) dies with cosim, mpirun and both ranks.
const fs::path kLiggghtsSphere =
    fs::path(COSIM_SOURCE_DIR) / "tests" / "liggghts" / "data" / "settling-sphere-liggghts";

TEST(KilledOrchestrator, ExternalLiggghtsParticipantStopsWithinSeconds) {
  const std::string exe = std::string(COSIM_BIN_DIR) + "/cosim-liggghts";
  if (!fs::exists(exe)) GTEST_SKIP() << exe << " not built (COSIM_BUILD_LIGGGHTS=OFF)";
  const fs::path run = freshFolder("liggghts-external") / "run";
  auto cosim = startCosim(run, {"participants.particles.launch=external"}, kLiggghtsSphere);
  const auto args = externalArguments(run.string() + ".out", "particles");
  ASSERT_FALSE(args.empty()) << readFile(run.string() + ".out");
  std::vector<std::string> argv = {exe};
  argv.insert(argv.end(), args.begin(), args.end());
  const fs::path plog = run.string() + ".particles.log";
  util::ChildProcess particles(argv, ".", plog, {});
  ASSERT_TRUE(waitFor(60, [&] { return rows(run) > 5; })) << readFile(run.string() + ".out");

  ::kill(cosim.pid(), SIGKILL);
  const auto killed = Clock::now();
  EXPECT_TRUE(waitFor(30, [&] { return !particles.running(); }));
  const double gone = secondsSince(killed);
  std::printf("external cosim-liggghts stopped %.2f s after cosim was killed\n", gone);
  EXPECT_LT(gone, 10.0);  // 3 s, then at most 5 s more if LIGGGHTS is in the middle of a step
  EXPECT_EQ(particles.exitCode(), 3) << particles.exitDescription();
  EXPECT_NE(readFile(plog).find("is gone: no connection to it for"), std::string::npos)
      << readFile(plog);
  cosim.wait();
}

TEST(KilledOrchestrator, LocalLiggghtsUnderMpirunDiesWithItRanksAndAll) {
  const std::string exe = std::string(COSIM_BIN_DIR) + "/cosim-liggghts";
  if (!fs::exists(exe)) GTEST_SKIP() << exe << " not built (COSIM_BUILD_LIGGGHTS=OFF)";
  const fs::path run = freshFolder("liggghts-mpi") / "run";
  auto cosim = startCosim(run, {"participants.particles.mpi=2"}, kLiggghtsSphere);
  ASSERT_TRUE(waitFor(60, [&] { return rows(run) > 5; })) << readFile(run.string() + ".out");
  std::vector<pid_t> all = childrenOf(cosim.pid());  // the fluid and mpirun
  for (pid_t child : std::vector<pid_t>(all)) {
    const auto ranks = childrenOf(child);
    all.insert(all.end(), ranks.begin(), ranks.end());
  }
  ASSERT_GE(all.size(), 4u) << "expected the fluid, mpirun and two ranks";

  ::kill(cosim.pid(), SIGKILL);
  const auto killed = Clock::now();
  EXPECT_TRUE(waitFor(
      30, [&] { return std::none_of(all.begin(), all.end(), [](pid_t p) { return alive(p); }); }));
  const double gone = secondsSince(killed);
  std::printf("fluid, mpirun and 2 LIGGGHTS ranks gone %.2f s after cosim was killed\n", gone);
  EXPECT_LT(gone, 10.0);
  cosim.wait();
}

// Open MPI's shared-memory backing files (a few MB a rank in /dev/shm) stay behind when ranks are
// killed; the ranks cosim starts with mpirun on this host keep them in a folder of the run's,
// which the run removes when it ends, however it ends.
TEST(KilledRanks, LeaveNoSharedMemoryBehind) {
  const std::string exe = std::string(COSIM_BIN_DIR) + "/cosim-liggghts";
  if (!fs::exists(exe)) GTEST_SKIP() << exe << " not built (COSIM_BUILD_LIGGGHTS=OFF)";
  if (!fs::is_directory("/dev/shm")) GTEST_SKIP() << "no /dev/shm";
  const fs::path run = freshFolder("liggghts-mpi-shm") / "run";
  auto cosim = startCosim(run, {"participants.particles.mpi=2"}, kLiggghtsSphere);
  ASSERT_TRUE(waitFor(60, [&] { return rows(run) > 5; })) << readFile(run.string() + ".out");
  std::string run_id;
  {
    const std::string log = readFile(run / "cosim.log");
    const std::string flag = "--run-id, ";
    const auto at = log.find(flag);
    ASSERT_NE(at, std::string::npos) << log;
    run_id =
        log.substr(at + flag.size(), log.find_first_of(",\n", at + flag.size()) - at - flag.size());
  }
  const fs::path folder =
      fs::path("/dev/shm") / ("cosim-" + std::to_string(getuid()) + "-" + run_id + "-mpi");
  std::size_t segments = 0;
  for (const auto& e : fs::directory_iterator(folder))
    segments += e.path().filename().string().rfind("vader_segment", 0) == 0;
  EXPECT_EQ(segments, 2u) << "one backing file a LIGGGHTS rank in " << folder;

  // The ranks killed (as an out-of-memory kill would): nothing cleans up after them but cosim
  std::vector<pid_t> ranks;
  for (pid_t child : childrenOf(cosim.pid()))
    for (pid_t grandchild : childrenOf(child)) ranks.push_back(grandchild);
  ASSERT_EQ(ranks.size(), 2u) << "expected mpirun's two LIGGGHTS ranks";
  for (pid_t r : ranks) ::kill(r, SIGKILL);
  EXPECT_TRUE(waitFor(60, [&] { return !cosim.running(); })) << "cosim still running";
  cosim.wait();
  EXPECT_FALSE(fs::exists(folder)) << folder << " left behind";
}

// Only sockets nothing listens on and older than a minute are removed; a live run's socket and
// files that are not sockets are kept, however old.
TEST(SocketFolder, RemovesOnlyDeadOldSockets) {
  const fs::path dir = privateSocketFolder();
  const std::string tag = "cosim-test-" + std::to_string(getpid());
  auto bindSocket = [](const fs::path& p, bool listening) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", p.c_str());
    EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0) << p;
    if (listening) {
      EXPECT_EQ(::listen(fd, 1), 0);
      return fd;
    }
    ::close(fd);  // the file stays: a dead socket
    return -1;
  };
  const auto old = fs::file_time_type::clock::now() - std::chrono::minutes(5);
  const fs::path dead_old = dir / (tag + "-dead-old.ipc");
  const fs::path dead_young = dir / (tag + "-dead-young.ipc");
  const fs::path live_old = dir / (tag + "-live-old.ipc");
  const fs::path plain_old = dir / (tag + "-plain-old.ipc");
  bindSocket(dead_old, false);
  bindSocket(dead_young, false);
  const int live = bindSocket(live_old, true);
  std::ofstream(plain_old) << "not a socket\n";
  for (const auto& p : {dead_old, live_old, plain_old}) fs::last_write_time(p, old);

  privateSocketFolder();
  EXPECT_FALSE(fs::exists(fs::symlink_status(dead_old)));
  EXPECT_TRUE(fs::exists(fs::symlink_status(dead_young)));
  EXPECT_TRUE(fs::exists(fs::symlink_status(live_old)));
  EXPECT_TRUE(fs::exists(plain_old));
  ::close(live);
  for (const auto& p : {dead_young, live_old, plain_old}) fs::remove(p);
}

// ---- strangers at the orchestrator's socket --------------------------------------------------

namespace {

// What a rogue client sends: forged Hellos under the participants' names and others.
enum class Forgery { no_token, wrong_token, wrong_version, garbage, forged_reply };

wire::Envelope forgedHello(const std::string& name, Forgery kind) {
  wire::Envelope e;
  auto* h = e.mutable_header();
  h->set_protocol_version(kind == Forgery::wrong_version ? 99 : wire::PROTOCOL_VERSION);
  h->set_participant(name);
  if (kind == Forgery::wrong_token) h->set_token("0123456789abcdef0123456789abcdef");
  if (kind == Forgery::forged_reply) {
    h->set_token("not the token");
    auto* adv = e.mutable_advanced();
    adv->mutable_state()->add_ids(1);
    return e;
  }
  auto* hello = e.mutable_hello();
  hello->set_role(name == "fluid" ? wire::FLUID : wire::PARTICLES);
  hello->set_adapter("rogue");
  hello->add_provides(field::position);
  hello->add_provides(field::velocity);
  hello->add_provides(field::radius);
  return e;
}

// Sends forged messages to `endpoint` until `stop`: each from a new connection under one of
// the participants' names (or a stranger's), waiting briefly for an answer. Counts the
// Refused answers.
struct Rogue {
  std::atomic<bool> stop{false};
  std::atomic<int> sent{0}, refused{0};
  std::thread thread;

  void start(const std::string& endpoint) {
    thread = std::thread([this, endpoint] {
      const std::vector<std::string> names = {"particles", "fluid", "stranger", "particles#hb"};
      const std::vector<Forgery> kinds = {Forgery::no_token, Forgery::wrong_token,
                                          Forgery::wrong_version, Forgery::garbage,
                                          Forgery::forged_reply};
      for (std::size_t i = 0; !stop; ++i) {
        const std::string& name = names[i % names.size()];
        const Forgery kind = kinds[(i / names.size()) % kinds.size()];
        link::Channel ch(endpoint, name);
        const auto t0 = Clock::now();
        while (ch.timeWithoutConnection().count() != 0 && secondsSince(t0) < 1.0)
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        if (kind == Forgery::garbage) {
          ch.sendRaw("\x08\x96\x01 garbage, not an envelope");
        } else {
          ch.send(forgedHello(name, kind));
        }
        ++sent;
        try {
          if (auto r = ch.receive(link::Millis(50)); r && r->has_refused()) ++refused;
        } catch (const std::exception&) {
        }
      }
    });
  }
  void finish() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
};

}  // namespace

// A forged or wrong-version Hello from a stranger, garbage under a participant's name, a forged
// reply: all dropped (a Hello answered with Refused), one log line per sender, while the run
// completes with the exact result. Before the token, one such Hello aborted the run, or was
// accepted as the participant. The particles participant is external, so that the stranger
// holds its name first: the real one joins after the stranger's Hellos were refused.
TEST(Strangers, ForgedHellosNeitherAbortNorJoinTheRun) {
  const std::string ep = "ipc:///tmp/cosim-rogue-" + std::to_string(getpid()) + ".ipc";
  Scenario sc = loadScenario(kSphere, {"transport.bind=" + ep, "coupling.end_time=0.05",
                                       "participants.particles.launch=external"});
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("rogue");
  Rogue rogue;
  rogue.start(ep);
  int particles_exit = -1;
  // The thread that starts a process must outlive it (its parent-death signal is per thread).
  std::thread starter([&] {
    if (!waitFor(20, [&] { return rogue.refused >= 3; })) return;
    std::vector<std::string> argv = {std::string(COSIM_BIN_DIR) + "/cosim-free-particles"};
    const auto args = externalArguments(o.output / "cosim.log", "particles");
    argv.insert(argv.end(), args.begin(), args.end());
    util::ChildProcess particles(argv, ".", o.output.string() + ".particles.log", {});
    particles_exit = particles.wait();
  });
  Coupler c(std::move(sc), o);
  double t_last = 0.0, vz_last = 0.0;
  std::size_t steps = 0;
  c.on_step = [&](double t, const link::ParticleData& s) {
    ++steps;
    t_last = t;
    vz_last = s.get(field::velocity)[2];
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // let the rogue in meanwhile
  };
  RunResult r = c.run();
  rogue.finish();
  starter.join();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(steps, 500u);
  // The undisturbed result: Stokes settling, v = -v_t (1 - exp(-t / tau)) (hand values as in
  // end_to_end_test: v_t = 2.0437e-3 m/s, tau = rho_p d^2 / (18 mu) = 3.47e-4 s).
  const double vt = 1500 * 9.81 * 2.5e-9 / 0.018, tau = 2500 * 2.5e-9 / 0.018;
  EXPECT_NEAR(vz_last, -vt * (1 - std::exp(-t_last / tau)), 1e-9 * vt);
  EXPECT_GT(rogue.sent, 40) << "the rogue hardly sent anything";
  EXPECT_GE(rogue.refused, 3) << "a stranger's Hello is answered with Refused";
  const std::string log = readFile(r.folder / "cosim.log");
  EXPECT_TRUE(std::regex_search(
      log,
      std::regex("ignored messages from 'particles': a message with(out a| a wrong) run token")))
      << log;
  EXPECT_NE(log.find("ignored messages from 'stranger': not a participant of this run"),
            std::string::npos);
  EXPECT_LT(log.size(), 20000u) << "one line per sender, not per message";
  EXPECT_EQ(particles_exit, 0) << readFile(o.output.string() + ".particles.log");
}

// A participant that carries the run's token but speaks another protocol version is one of the
// run's own (an adapter from another cosim version): refused with the versions, and the run
// stops with that reason.
TEST(Strangers, OwnParticipantOfAnotherVersionIsRefusedWithTheVersions) {
  const std::string ep = "ipc:///tmp/cosim-version-" + std::to_string(getpid()) + ".ipc";
  Scenario sc = loadScenario(kSphere, {"transport.bind=" + ep, "transport.handshake_timeout=20",
                                       "participants.particles.launch=external"});
  RunOptions o;
  o.quiet = true;
  o.output = freshFolder("version");
  std::string refusal;
  std::thread participant([&] {
    const fs::path token_file = o.output / kRunTokenFile;
    if (!waitFor(10, [&] { return fs::exists(token_file); })) return;
    link::Channel ch(ep, "particles");
    wire::Envelope hello = forgedHello("particles", Forgery::wrong_version);
    hello.mutable_header()->set_token(readFile(token_file).substr(0, 32));
    ch.send(hello);
    if (auto r = ch.receive(link::Millis(10000)); r && r->has_refused())
      refusal = r->refused().reason();
  });
  Coupler c(std::move(sc), o);
  RunResult r = c.run();
  participant.join();
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.message.find("protocol version 99"), std::string::npos) << r.message;
  EXPECT_NE(refusal.find("protocol version 99 but the orchestrator speaks version " +
                         std::to_string(wire::PROTOCOL_VERSION)),
            std::string::npos)
      << refusal;
  EXPECT_FALSE(fs::exists(o.output / kRunTokenFile)) << "the token file outlived the run";
}

TEST(RunToken, IsRandomAndComparedWhole) {
  const std::string a = newRunToken(), b = newRunToken();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos) << a;
  EXPECT_NE(a, b);
  EXPECT_TRUE(sameToken(a, a));
  EXPECT_FALSE(sameToken(b, a));
  EXPECT_FALSE(sameToken(a.substr(0, 31), a));
  EXPECT_FALSE(sameToken("", ""));  // an empty token never proves anything
}
