// The CI coating bed with the real solvers (OpenFOAM + LIGGGHTS, started by cosim) over tcp://
// with CurveZMQ, through a relay that reads the wire, while a stranger without keys knocks: the
// run completes with its precursor balance closed and the same numbers, to the bit, as the run
// over ipc://; the stranger is refused; and the parcels' final positions (sent in the last
// Advanced) are nowhere in the bytes on the wire.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "../orchestrator/tcp_relay.h"
#include "cosim/link/curve_keys.h"
#include "cosim/link/fields.h"
#include "cosim/link/transport.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(PlasmaCoatingCi, OverTcpWithCurveZmqTheWireIsUnreadableAndTheBalanceCloses) {
  ASSERT_TRUE(cosim::link::curveAvailable()) << "this libzmq has no CurveZMQ";
  const fs::path dir = fs::temp_directory_path() / ("cosim-ci-curve-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path key_file = dir / "orchestrator.key";
  cosim::link::writeKeyPairFile(key_file, cosim::link::newCurveKeyPair());
  const int port = cosim::test::freeLoopbackPort();
  const std::string ep = "tcp://127.0.0.1:" + std::to_string(port);
  cosim::test::TcpRelay relay(port);
  Scenario sc = loadScenario(
      fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml",
      {"transport.bind=" + ep, "transport.connect=tcp://127.0.0.1:" + std::to_string(relay.port()),
       "transport.key_file=" + key_file.string()});
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";

  // A stranger without keys, twice a second all through the run.
  std::atomic<bool> stop{false};
  std::atomic<int> knocks{0}, answers{0};
  std::thread stranger([&] {
    while (!stop) {
      try {
        cosim::link::Channel ch(ep, "particles");
        cosim::wire::Envelope e;
        e.mutable_header()->set_participant("particles");
        e.mutable_hello()->set_role(cosim::wire::PARTICLES);
        ch.send(e);
        if (ch.receive(cosim::link::Millis(500))) ++answers;
      } catch (const std::exception&) {
      }
      ++knocks;
    }
  });
  RunResult r = Coupler(std::move(sc), o).run();
  stop = true;
  stranger.join();
  ASSERT_EQ(r.exit_code, 0) << r.message;

  // The same scene over ipc:// (the default link): the transport changes no number.
  RunOptions ipc_o;
  ipc_o.quiet = true;
  ipc_o.output = dir / "ipc";
  RunResult ipc =
      Coupler(loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml"),
              ipc_o)
          .run();
  ASSERT_EQ(ipc.exit_code, 0) << ipc.message;
  EXPECT_EQ(r.final_state.ids, ipc.final_state.ids);
  EXPECT_EQ(r.final_state.get(cosim::field::position), ipc.final_state.get(cosim::field::position));
  EXPECT_EQ(r.final_state.get(cosim::field::coating_mass),
            ipc.final_state.get(cosim::field::coating_mass));
  for (const auto& [name, value] : ipc.totals) EXPECT_EQ(r.totals.at(name), value) << name;

  // The run's result: the precursor balance closes as in MassBalanceClosesAndReportIsProduced.
  const double in = r.totals.at("precursor_in_kg");
  const double removed = r.totals.at("precursor_removed_kg");
  const double expected = in - r.totals.at("precursor_out_kg") - r.totals.at("precursor_held_kg");
  ASSERT_GT(in, 0.0);
  EXPECT_GT(removed, 0.0);
  EXPECT_LT(std::fabs(expected - removed), 1e-4 * in);
  EXPECT_NEAR(r.totals.at("coating_credited_kg"), removed, 1e-12 * removed);
  ASSERT_EQ(r.final_state.size(), 1500u);

  // The wire: every step's particle data went through the relay (at least the 1500 positions,
  // 3 x 8 bytes each, of 500 Advanced replies), and none of the last positions is readable.
  EXPECT_GT(relay.total(), 500u * 1500u * 24u);
  const std::string wire = relay.captured();
  const auto& x = r.final_state.get(cosim::field::position);
  std::size_t found = 0;
  for (std::size_t i = 0; i < 3 * 200; ++i) found += cosim::test::containsDouble(wire, x[i]);
  EXPECT_EQ(found, 0u) << "parcel positions readable on the wire";

  const std::string log = [&] {
    std::ifstream f(r.folder / "cosim.log");
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }();
  EXPECT_NE(log.find("(CurveZMQ)"), std::string::npos);
  EXPECT_GT(knocks, 2);
  EXPECT_EQ(answers, 0) << "the stranger got an answer";
  EXPECT_NE(log.find("refused a connection from tcp://127.0.0.1:"), std::string::npos) << log;
  fs::remove_all(dir);
}
