// Security on tcp:// (issue 17): CurveZMQ key files, the hub that lets in only the keys it
// issued, runs of the settling sphere over real tcp sockets while strangers knock (no keys,
// another run's keys, garbage), the bytes on the wire read through a relay, and the refusal of
// a tcp:// link that has neither keys nor transport.insecure.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cosim/link/curve_keys.h"
#include "cosim/link/fields.h"
#include "cosim/link/session.h"
#include "cosim/link/transport.h"
#include "cosim/util/child_process.h"
#include "coupler.h"
#include "link_security.h"
#include "scenario.h"
#include "tcp_relay.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const fs::path kSphere = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere";

fs::path freshFolder(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("cosim-curve-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  return p;
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

unsigned modeOf(const fs::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return 0;
  return st.st_mode & 0777;
}

template <class F>
bool waitFor(double seconds, F done) {
  const auto t0 = Clock::now();
  while (!done()) {
    if (std::chrono::duration<double>(Clock::now() - t0).count() > seconds) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// A fresh orchestrator key file in `folder`.
fs::path orchestratorKeyFile(const fs::path& folder) {
  fs::create_directories(folder);
  const fs::path file = folder / "orchestrator.key";
  link::writeKeyPairFile(file, link::newCurveKeyPair());
  return file;
}

// Bytes that open like ZeroMQ's greeting (its 10-byte signature) and go on with junk, so that
// the hub reads a whole greeting of nonsense rather than waiting for more.
std::string garbage() {
  std::string g(10, '\0');
  g[0] = '\xff';
  g[9] = '\x7f';
  return g + std::string(70, 'G') + "GET / HTTP/1.0\r\n\r\n";
}

wire::Envelope hello(const std::string& name) {
  wire::Envelope e;
  e.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
  e.mutable_header()->set_participant(name);
  e.mutable_hello()->set_role(wire::PARTICLES);
  return e;
}

// The settling sphere's undisturbed result (hand values as in end_to_end_test: Stokes settling
// of a 50 um glass sphere in water, v = -v_t (1 - exp(-t / tau)), v_t = 2.0437e-3 m/s,
// tau = rho_p d^2 / (18 mu) = 3.47e-4 s).
double stokesVelocity(double t) {
  const double vt = 1500 * 9.81 * 2.5e-9 / 0.018, tau = 2500 * 2.5e-9 / 0.018;
  return -vt * (1 - std::exp(-t / tau));
}

// Strangers at a tcp:// endpoint until stopped: ZeroMQ clients without keys, with keys of
// another run (a key pair the hub never issued, with the right orchestrator key), and raw
// garbage bytes on a plain TCP connection. Counts what they send and any answer they get.
struct Strangers {
  std::atomic<bool> stop{false};
  std::atomic<int> attempts{0}, answered{0};
  std::thread thread;

  void start(const std::string& endpoint, int port, const std::string& orchestrator_public) {
    thread = std::thread([this, endpoint, port, orchestrator_public] {
      for (int i = 0; !stop; ++i) {
        try {
          if (i % 3 == 2) {
            const int fd = test::connectLoopback(port);
            if (fd >= 0) {
              const std::string junk = garbage();
              (void)::write(fd, junk.data(), junk.size());
              std::this_thread::sleep_for(std::chrono::milliseconds(20));
              ::close(fd);
            }
          } else {
            link::CurveClientKeys keys;
            if (i % 3 == 1) keys = {orchestrator_public, link::newCurveKeyPair()};
            link::Channel ch(endpoint, "", keys);
            ch.send(hello("particles"));
            if (ch.receive(link::Millis(60))) ++answered;
          }
        } catch (const std::exception&) {
        }
        ++attempts;
      }
    });
  }
  void finish() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
};

// The NUL-separated entries of /proc/PID/<what> (cmdline, environ).
std::vector<std::string> procEntries(pid_t pid, const std::string& what) {
  const std::string text = readFile("/proc/" + std::to_string(pid) + "/" + what);
  std::vector<std::string> out;
  std::string::size_type at = 0;
  while (at < text.size()) {
    const auto end = text.find('\0', at);
    out.push_back(text.substr(at, end == std::string::npos ? std::string::npos : end - at));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return out;
}

// Processes whose parent is `parent`.
std::vector<pid_t> childrenOf(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string stat = readFile(e.path() / "stat");
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(stat.substr(close + 2));
    char state;
    pid_t ppid;
    rest >> state >> ppid;
    if (ppid == parent) out.push_back(std::stoi(name));
  }
  return out;
}

}  // namespace

// ---- keys and their files --------------------------------------------------------------------

TEST(CurveKeys, CosimKeysCreatesAPrivateFileAndNeverPrintsTheSecret) {
  ASSERT_TRUE(link::curveAvailable()) << "this libzmq has no CurveZMQ";
  const fs::path dir = freshFolder("keys");
  const fs::path file = dir / "sub" / "orchestrator.key";
  const fs::path out = dir.string() + ".out";
  fs::create_directories(dir);
  ASSERT_EQ(util::runProgram({COSIM_EXE, "keys", file.string()}, out), 0) << readFile(out);
  EXPECT_EQ(modeOf(file), 0600u);
  EXPECT_EQ(modeOf(file.parent_path()), 0700u);
  const link::CurveKeyPair pair = link::readKeyPairFile(file);
  const std::string first = readFile(out);
  EXPECT_NE(first.find("created orchestrator key file " + file.string()), std::string::npos)
      << first;
  EXPECT_NE(first.find(pair.public_key), std::string::npos) << first;
  EXPECT_EQ(first.find(pair.secret_key), std::string::npos) << "the secret key was printed";
  EXPECT_NE(first.find("--key-file"), std::string::npos) << "says how participants get keys";

  // Again: the same file, kept as it is.
  ASSERT_EQ(util::runProgram({COSIM_EXE, "keys", file.string()}, out), 0);
  EXPECT_NE(readFile(out).find("existing orchestrator key file"), std::string::npos);
  EXPECT_EQ(link::readKeyPairFile(file).secret_key, pair.secret_key);

  // Readable by others: refused, saying how to fix it.
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_NE(util::runProgram({COSIM_EXE, "keys", file.string()}, out), 0);
  EXPECT_NE(readFile(out).find("chmod 600"), std::string::npos) << readFile(out);

  // A participant's key file: shown with its public keys only.
  const link::CurveClientKeys k{pair.public_key, link::newCurveKeyPair()};
  const fs::path pf = dir / ".cosim-fluid.key";
  link::writeParticipantKeyFile(pf, k, "run-7", "fluid");
  EXPECT_EQ(modeOf(pf), 0600u);
  ASSERT_EQ(util::runProgram({COSIM_EXE, "keys", pf.string()}, out), 0) << readFile(out);
  const std::string shown = readFile(out);
  EXPECT_NE(shown.find("participant:             fluid"), std::string::npos) << shown;
  EXPECT_NE(shown.find(k.own.public_key), std::string::npos);
  EXPECT_EQ(shown.find(k.own.secret_key), std::string::npos) << "the secret key was printed";
  const link::ParticipantKeyFile back = link::readParticipantKeyFile(pf);
  EXPECT_EQ(back.run_id, "run-7");
  EXPECT_EQ(back.keys.own.secret_key, k.own.secret_key);
  EXPECT_EQ(back.keys.orchestrator_public, pair.public_key);
  fs::remove_all(dir);
}

TEST(CurveKeys, EnvironmentTextRoundTripsAndMalformedIsRefused) {
  const link::CurveClientKeys k{link::newCurveKeyPair().public_key, link::newCurveKeyPair()};
  const link::CurveClientKeys back = link::parseCurveKeysVariable(link::curveKeysVariableText(k));
  EXPECT_EQ(back.orchestrator_public, k.orchestrator_public);
  EXPECT_EQ(back.own.public_key, k.own.public_key);
  EXPECT_EQ(back.own.secret_key, k.own.secret_key);
  EXPECT_THROW(link::parseCurveKeysVariable("too short"), std::runtime_error);
  EXPECT_FALSE(link::isZ85Key(std::string(40, ' ')));
  EXPECT_TRUE(link::isZ85Key(k.own.public_key));
}

// ---- the hub ---------------------------------------------------------------------------------

// Only a client holding a key the hub was given gets its messages through; one without keys,
// one with a key the hub never issued, and garbage bytes reach nothing, are described (without
// keys) among the refusals, and the hub goes on serving its client.
TEST(CurveHub, LetsInOnlyTheKeysItIssued) {
  const link::CurveKeyPair server = link::newCurveKeyPair();
  const link::CurveKeyPair issued = link::newCurveKeyPair(), other = link::newCurveKeyPair();
  link::HubSecurity security{server, {issued.public_key}};
  const int port = test::freeLoopbackPort();
  const std::string ep = "tcp://127.0.0.1:" + std::to_string(port);
  link::Hub hub(ep, security);

  link::Channel own(ep, "", {server.public_key, issued});
  own.send(hello("particles"));
  auto in = hub.receive(link::Millis(5000));
  ASSERT_TRUE(in && in->envelope) << "the issued key was not let in";
  EXPECT_EQ(in->envelope->header().participant(), "particles");

  link::Channel plain(ep);
  plain.send(hello("plain"));
  link::Channel stranger(ep, "", {server.public_key, other});
  stranger.send(hello("stranger"));
  const int fd = test::connectLoopback(port);
  ASSERT_GE(fd, 0);
  const std::string junk = garbage();
  ASSERT_EQ(::write(fd, junk.data(), junk.size()), static_cast<ssize_t>(junk.size()));
  EXPECT_FALSE(hub.receive(link::Millis(1500))) << "a message got past the key check";
  EXPECT_TRUE(waitFor(5, [&] { return !stranger.handshakeFailure().empty(); }));
  EXPECT_NE(stranger.handshakeFailure().find("not one it issued"), std::string::npos)
      << stranger.handshakeFailure();
  ::close(fd);

  // The own client still gets through, both ways.
  own.send(hello("particles"));
  in = hub.receive(link::Millis(5000));
  ASSERT_TRUE(in && in->envelope);
  wire::Envelope reply;
  reply.mutable_header()->set_participant("particles");
  reply.mutable_refused()->set_reason("test");
  hub.send(in->peer, reply);
  auto back = own.receive(link::Millis(5000));
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->has_refused());

  std::string refusals;
  waitFor(5, [&] {
    for (const auto& l : hub.takeRefusals()) refusals += l + "\n";
    return refusals.find("its key was not issued for this run") != std::string::npos &&
           refusals.find("its security handshake failed") != std::string::npos;
  });
  EXPECT_NE(refusals.find("refused a connection from 127.0.0.1: its key was not issued for this "
                          "run"),
            std::string::npos)
      << refusals;
  EXPECT_NE(refusals.find("its security handshake failed"), std::string::npos) << refusals;
  for (const auto& key : {server.secret_key, other.public_key, other.secret_key, issued.secret_key})
    EXPECT_EQ(refusals.find(key), std::string::npos) << "a key in the refusals";
}

// ---- runs over tcp:// ------------------------------------------------------------------------

// The settling sphere over tcp:// with CurveZMQ, the particles participant external (started
// here with the key file the run prints), while strangers knock: none gets an answer, each is
// listed in cosim.log, and the run completes with the undisturbed result. The participant's key
// file is private while the run lasts and gone after it; the fluid cosim starts has its keys in
// its environment, not on its command line (what ps shows); no secret is in the run's files.
TEST(CurveRun, StrangersAreRefusedAndTheRunCompletes) {
  const fs::path dir = freshFolder("strangers");
  const fs::path key_file = orchestratorKeyFile(dir / "config");
  const link::CurveKeyPair server = link::readKeyPairFile(key_file);
  const int port = test::freeLoopbackPort();
  const std::string ep = "tcp://127.0.0.1:" + std::to_string(port);
  Scenario sc =
      loadScenario(kSphere, {"transport.bind=" + ep, "transport.key_file=" + key_file.string(),
                             "participants.particles.launch=external"});
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  Strangers strangers;
  strangers.start(ep, port, server.public_key);
  int particles_exit = -1;
  unsigned key_mode = 0;
  std::string participant_secret;
  std::thread starter([&] {
    // The arguments cosim prints for the external participant.
    std::vector<std::string> args;
    const std::string marker = "waiting for particles (launch: external): start it with ";
    waitFor(20, [&] {
      const std::string text = readFile(o.output / "cosim.log");
      const auto at = text.find(marker);
      if (at == std::string::npos || text.find('\n', at) == std::string::npos) return false;
      std::istringstream line(
          text.substr(at + marker.size(), text.find('\n', at) - at - marker.size()));
      for (std::string a; line >> a;) args.push_back(a);
      return true;
    });
    for (std::size_t i = 0; i + 1 < args.size(); ++i) {
      if (args[i] == "--key-file") {
        key_mode = modeOf(args[i + 1]);
        participant_secret = link::readParticipantKeyFile(args[i + 1]).keys.own.secret_key;
      }
    }
    std::vector<std::string> argv = {std::string(COSIM_BIN_DIR) + "/cosim-free-particles"};
    argv.insert(argv.end(), args.begin(), args.end());
    util::ChildProcess particles(argv, ".", dir.string() + "/particles.out", {});
    particles_exit = particles.wait();
  });
  Coupler c(std::move(sc), o);
  double t_last = 0.0, vz_last = 0.0;
  std::size_t steps = 0;
  // The fluid, started by cosim: its keys are in its environment, not on its command line.
  std::string fluid_secret, fluid_cmdline;
  c.on_step = [&](double t, const link::ParticleData& s) {
    ++steps;
    t_last = t;
    vz_last = s.get(field::velocity)[2];
    if (steps == 1) {
      for (pid_t child : childrenOf(getpid())) {
        const auto argv = procEntries(child, "cmdline");
        if (argv.empty() || argv[0].find("cosim-analytic-fluid") == std::string::npos) continue;
        for (const auto& a : argv) fluid_cmdline += a + " ";
        for (const auto& v : procEntries(child, "environ")) {
          const std::string var = std::string(link::kCurveKeysVariable) + "=";
          if (v.rfind(var, 0) == 0)
            fluid_secret = link::parseCurveKeysVariable(v.substr(var.size())).own.secret_key;
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // let the strangers in meanwhile
  };
  const auto t0 = Clock::now();
  RunResult r = c.run();
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  strangers.finish();
  starter.join();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(particles_exit, 0) << readFile(dir / "particles.out");
  EXPECT_EQ(steps, 50u);
  EXPECT_NEAR(vz_last, stokesVelocity(t_last), 1e-9 * 2.0437e-3);
  EXPECT_GT(strangers.attempts, 6) << "the strangers hardly tried";
  EXPECT_EQ(strangers.answered, 0) << "a stranger got an answer";
  EXPECT_LT(seconds, 30.0);
  const std::string log = readFile(r.folder / "cosim.log");
  EXPECT_NE(log.find("orchestrator at " + ep + " (CurveZMQ)"), std::string::npos) << log;
  EXPECT_NE(log.find("refused a connection from 127.0.0.1: its key was not issued for this run"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("refused a connection from tcp://127.0.0.1:"), std::string::npos) << log;
  EXPECT_LT(log.size(), 20000u) << "at most 20 lines about refused connections";
  EXPECT_EQ(key_mode, 0600u) << "the participant's key file must be private";
  ASSERT_EQ(participant_secret.size(), 40u);
  EXPECT_FALSE(fs::exists(o.output / ".cosim-particles.key")) << "the key file outlived the run";
  ASSERT_EQ(fluid_secret.size(), 40u) << "the fluid's keys are not in its environment";
  EXPECT_NE(fluid_cmdline.find("--endpoint " + ep), std::string::npos) << fluid_cmdline;
  EXPECT_EQ(fluid_cmdline.find(fluid_secret), std::string::npos) << "a key on the command line";
  EXPECT_EQ(fluid_cmdline.find(server.public_key), std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(r.folder)) {
    if (!e.is_regular_file()) continue;
    const std::string text = readFile(e.path());
    for (const auto& secret : {participant_secret, fluid_secret, server.secret_key})
      EXPECT_EQ(text.find(secret), std::string::npos) << "a secret key in " << e.path();
  }
  fs::remove_all(dir);
}

// The bytes on the wire, read through a relay between the participants and the orchestrator:
// with CurveZMQ the particle's position (a value only the particle data holds, 8 bytes as
// protobuf packs a double) is nowhere in them; over insecure tcp:// the same run shows it, so
// the check can see it when it is there.
TEST(CurveRun, ParticlePacketsOnTheWireAreNotReadable) {
  const double x0 = 0.012345678901234567, y0 = -0.0234567890123456;
  const std::string particle = "participants.particles.options.particles=[{id: 1, position: [" +
                               fmt::format("{:.17g}, {:.17g}", x0, y0) +
                               ", 0], velocity: [0, 0, 0], radius: 25.0e-6}]";
  const fs::path dir = freshFolder("wire");
  const fs::path key_file = orchestratorKeyFile(dir / "config");
  for (const bool insecure : {true, false}) {
    SCOPED_TRACE(insecure ? "insecure" : "CurveZMQ");
    const int port = test::freeLoopbackPort();
    test::TcpRelay relay(port);
    Scenario sc = loadScenario(
        kSphere, {"transport.bind=tcp://127.0.0.1:" + std::to_string(port),
                  "transport.connect=tcp://127.0.0.1:" + std::to_string(relay.port()),
                  "transport.key_file=" + key_file.string(),
                  std::string("transport.insecure=") + (insecure ? "true" : "false"), particle});
    RunOptions o;
    o.quiet = true;
    o.output = dir / (insecure ? "insecure" : "curve");
    double x_last = 0.0, y_last = 0.0;
    Coupler c(std::move(sc), o);
    c.on_step = [&](double, const link::ParticleData& s) {
      x_last = s.get(field::position)[0];
      y_last = s.get(field::position)[1];
    };
    RunResult r = c.run();
    ASSERT_EQ(r.exit_code, 0) << r.message;
    ASSERT_EQ(x_last, x0) << "the particle moved sideways: the known value is not on the wire";
    ASSERT_EQ(y_last, y0);
    EXPECT_GE(relay.connections(), 2) << "the participants did not go through the relay";
    const std::string wire = relay.captured();
    // 50 steps of Sample, Samples, Advance and Advanced, each with at least 8 bytes per field.
    EXPECT_GT(wire.size(), 50u * 4u * 8u);
    EXPECT_EQ(test::containsDouble(wire, x0), insecure);
    EXPECT_EQ(test::containsDouble(wire, y0), insecure);
    const std::string log = readFile(r.folder / "cosim.log");
    EXPECT_EQ(log.find("transport.insecure: the link at tcp://127.0.0.1:" + std::to_string(port) +
                       " is neither encrypted nor authenticated") != std::string::npos,
              insecure)
        << log;
  }
  fs::remove_all(dir);
}

// tcp:// with neither a key file nor transport.insecure: refused before anything starts, naming
// both ways out; binding every interface is refused at once.
TEST(CurveRun, TcpWithoutKeysIsRefusedNamingTransportInsecure) {
  const fs::path dir = freshFolder("nokeys");
  const fs::path missing = dir / "no-such.key";
  Scenario sc = loadScenario(
      kSphere, {"transport.bind=tcp://127.0.0.1:" + std::to_string(test::freeLoopbackPort()),
                "transport.key_file=" + missing.string()});
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  RunResult r = Coupler(std::move(sc), o).run();
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.message.find(missing.string() + " does not exist"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("cosim keys"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("transport.insecure: true"), std::string::npos) << r.message;

  try {
    loadScenario(kSphere, {"transport.bind=tcp://*:5555"});
    ADD_FAILURE() << "tcp://*:5555 was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("binds every interface"), std::string::npos) << e.what();
  }
  // tcp://:PORT: the address of this host's name.
  const std::string bound = bindAddress("tcp://:5555");
  EXPECT_EQ(bound.rfind("tcp://", 0), 0u);
  EXPECT_EQ(bound.substr(bound.size() - 5), ":5555");
  EXPECT_NE(bound, "tcp://:5555");
  EXPECT_EQ(bindAddress("ipc:///tmp/x.ipc"), "ipc:///tmp/x.ipc");
  fs::remove_all(dir);
}

// An external participant holding the key file of another run is refused by the orchestrator
// and says so, instead of only timing out.
TEST(CurveRun, ParticipantWithAnotherRunsKeyFileSaysItWasRefused) {
  const fs::path dir = freshFolder("oldkey");
  const fs::path key_file = orchestratorKeyFile(dir / "config");
  const link::CurveKeyPair server = link::readKeyPairFile(key_file);
  const int port = test::freeLoopbackPort();
  const std::string ep = "tcp://127.0.0.1:" + std::to_string(port);
  link::Hub hub(ep, {server, {link::newCurveKeyPair().public_key}});
  const fs::path old = dir / ".cosim-particles.key";
  link::writeParticipantKeyFile(old, {server.public_key, link::newCurveKeyPair()}, "old-run",
                                "particles");
  link::ParticipantOptions po;
  po.endpoint = ep;
  po.name = "particles";
  po.curve = link::readParticipantKeyFile(old).keys;
  po.handshake_timeout_ms = 3000;
  link::Capabilities caps;
  caps.role = wire::PARTICLES;
  caps.adapter = "test";
  std::string error;
  try {
    link::Session session(po, caps);
    session.handshake();
  } catch (const std::exception& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("refused this participant's CurveZMQ key"), std::string::npos) << error;
  EXPECT_FALSE(hub.receive(link::Millis(10)));
  fs::remove_all(dir);
}

// `cosim validate` says whether the link is encrypted.
TEST(CurveRun, ValidateSaysWhetherTheLinkIsEncrypted) {
  const fs::path dir = freshFolder("validate");
  fs::create_directories(dir);
  const fs::path out = dir / "validate.out";
  ASSERT_EQ(util::runProgram({COSIM_EXE, "validate", kSphere.string(), "--set",
                              "transport.bind=tcp://127.0.0.1:5555", "--set",
                              "transport.key_file=" + (dir / "k.key").string()},
                             out),
            0)
      << readFile(out);
  EXPECT_NE(readFile(out).find("link: tcp://127.0.0.1:5555 encrypted and authenticated with "
                               "CurveZMQ"),
            std::string::npos)
      << readFile(out);
  EXPECT_NE(readFile(out).find("create it with 'cosim keys'"), std::string::npos);
  ASSERT_EQ(
      util::runProgram({COSIM_EXE, "validate", kSphere.string(), "--set",
                        "transport.bind=tcp://127.0.0.1:5555", "--set", "transport.insecure=true"},
                       out),
      0);
  EXPECT_NE(readFile(out).find("link: tcp://127.0.0.1:5555 NOT encrypted"), std::string::npos)
      << readFile(out);
  ASSERT_EQ(util::runProgram({COSIM_EXE, "validate", kSphere.string()}, out), 0);
  EXPECT_NE(readFile(out).find("link: ipc:// in /tmp/cosim-"), std::string::npos) << readFile(out);
  fs::remove_all(dir);
}

// The run's external participant started with a key file of another run (the right
// orchestrator, keys it did not issue): the adapter stops at once with the reason, and the run,
// its participant never joining, says at its handshake timeout that connections were refused.
TEST(CurveRun, ExternalParticipantWithAnotherRunsKeysStopsAndTheRunSaysWhy) {
  const fs::path dir = freshFolder("stale");
  const fs::path key_file = orchestratorKeyFile(dir / "config");
  const link::CurveKeyPair server = link::readKeyPairFile(key_file);
  const int port = test::freeLoopbackPort();
  const std::string ep = "tcp://127.0.0.1:" + std::to_string(port);
  Scenario sc = loadScenario(
      kSphere, {"transport.bind=" + ep, "transport.key_file=" + key_file.string(),
                "transport.handshake_timeout=6", "participants.particles.launch=external"});
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  int particles_exit = -1;
  const fs::path particles_out = dir / "particles.out";
  std::thread starter([&] {
    const fs::path own = o.output / ".cosim-particles.key";
    if (!waitFor(10, [&] { return fs::exists(own); })) return;
    // The file of an earlier run of the same orchestrator: its keys were never issued here.
    const link::ParticipantKeyFile current = link::readParticipantKeyFile(own);
    const fs::path stale = dir / "stale.key";
    link::writeParticipantKeyFile(stale, {server.public_key, link::newCurveKeyPair()}, "",
                                  "particles");
    particles_exit = util::runProgram(
        {std::string(COSIM_BIN_DIR) + "/cosim-free-particles", "--endpoint", ep, "--name",
         "particles", "--run-id", current.run_id, "--key-file", stale.string()},
        particles_out);
  });
  const auto t0 = Clock::now();
  RunResult r = Coupler(std::move(sc), o).run();
  starter.join();
  EXPECT_EQ(particles_exit, 3) << readFile(particles_out);
  EXPECT_NE(readFile(particles_out)
                .find("does not let this participant in: the orchestrator refused this "
                      "participant's CurveZMQ key (ZAP status 400)"),
            std::string::npos)
      << readFile(particles_out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.message.find("did not connect within 6 s"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("connections were refused at the security handshake meanwhile "
                           "('refused a connection from 127.0.0.1: its key was not issued for "
                           "this run' in cosim.log)"),
            std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("--key-file " + (o.output / ".cosim-particles.key").string()),
            std::string::npos)
      << r.message;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 20.0);
  fs::remove_all(dir);
}
