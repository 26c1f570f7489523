// Wire protocol: round trips, version and step checks, garbage bytes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <random>
#include <thread>

#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/session.h"
#include "cosim/link/transport.h"
#include "cosim/models/parcels.h"

using namespace cosim;

namespace {

std::string endpoint(const std::string& tag) {
  return "ipc:///tmp/cosim-test-" + tag + "-" + std::to_string(getpid()) + ".ipc";
}

link::ParticleData sampleData() {
  link::ParticleData d;
  d.ids = {7, 3, 11};
  auto& x = d.field(field::position);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.1 * static_cast<double>(i) - 0.05;
  d.field(field::radius) = {1e-4, 2e-4, 3e-4};
  return d;
}

}  // namespace

TEST(Protocol, ParticleDataRoundTripKeepsIdsOrderAndValues) {
  const auto d = sampleData();
  wire::Envelope env;
  cosim::link::toWire(d, *env.mutable_advance()->mutable_terms());
  env.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
  env.mutable_header()->set_step(5);
  env.mutable_header()->set_time(0.25);
  const std::string bytes = link::serialize(env);
  const auto back = link::parse(bytes.data(), bytes.size());
  EXPECT_EQ(back.header().step(), 5u);
  EXPECT_DOUBLE_EQ(back.header().time(), 0.25);
  const auto d2 = cosim::link::fromWire(back.advance().terms());
  EXPECT_EQ(d2.ids, d.ids);
  EXPECT_EQ(d2.get(field::position), d.get(field::position));
  EXPECT_EQ(d2.get(field::radius), d.get(field::radius));
}

TEST(Protocol, PackedArraysNotOneMessagePerParticle) {
  // 10,000 particles with a 3-vector: the packet must be close to the raw size of the doubles.
  link::ParticleData d;
  d.ids.resize(10000);
  for (std::size_t i = 0; i < d.ids.size(); ++i) d.ids[i] = static_cast<std::int64_t>(i);
  d.field(field::velocity).assign(30000, 1.5);
  wire::Envelope env;
  cosim::link::toWire(d, *env.mutable_advanced()->mutable_state());
  const auto bytes = link::serialize(env);
  EXPECT_LT(bytes.size(), 30000 * 8 + 10000 * 3 + 200);
}

TEST(Protocol, FieldWithWrongLengthIsRefusedNamingTheField) {
  wire::FieldSet fs;
  fs.add_ids(1);
  fs.add_ids(2);
  auto* f = fs.add_fields();
  f->set_name(field::velocity);
  f->set_components(3);
  f->add_values(1.0);  // 1 value for 2 particles x 3 components
  try {
    cosim::link::fromWire(fs);
    FAIL() << "accepted a short field";
  } catch (const link::ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("velocity"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected 6"), std::string::npos) << e.what();
  }
}

TEST(Protocol, UnknownFieldIsRefused) {
  wire::FieldSet fs;
  fs.add_ids(1);
  auto* f = fs.add_fields();
  f->set_name("temperature_of_the_moon");
  f->set_components(1);
  f->add_values(1.0);
  EXPECT_THROW(cosim::link::fromWire(fs), link::ProtocolError);
}

TEST(Protocol, RandomBytesAreRefusedWithoutCrash) {
  std::mt19937 rng(42);
  int refused = 0;
  for (int n = 0; n < 2000; ++n) {
    std::string bytes(static_cast<std::size_t>(rng() % 200), '\0');
    for (auto& c : bytes) c = static_cast<char>(rng() & 0xff);
    try {
      auto env = link::parse(bytes.data(), bytes.size());
      // Bytes that happen to decode must still carry a header and a body.
      EXPECT_TRUE(env.has_header());
      EXPECT_NE(env.body_case(), wire::Envelope::BODY_NOT_SET);
    } catch (const link::ProtocolError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 1900);
}

// A string that is not UTF-8 makes the message undecodable: a ProtocolError, and no line of
// protobuf's own on stderr (a stranger sending such messages must not fill the console).
TEST(Protocol, TextThatIsNotUtf8IsRefusedWithoutALineOnStderr) {
  wire::Envelope env;
  env.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
  env.mutable_header()->set_run_id("AAAA");
  env.mutable_heartbeat()->set_sequence(1);
  std::string bytes = link::serialize(env);
  bytes.replace(bytes.find("AAAA"), 4, "\xff\xfe\xff\xfe");
  testing::internal::CaptureStderr();
  EXPECT_THROW(link::parse(bytes.data(), bytes.size()), link::ProtocolError);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Protocol, HubReportsGarbageFromAPeerInsteadOfCrashing) {
  const auto ep = endpoint("garbage");
  link::Hub hub(ep);
  link::Channel ch(ep, "fluid");
  ch.sendRaw("\xff\xfe this is not protobuf \x01\x02");
  auto in = hub.receive(link::Millis(2000));
  ASSERT_TRUE(in.has_value());
  EXPECT_EQ(in->peer, "fluid");
  EXPECT_FALSE(in->envelope.has_value());
  EXPECT_FALSE(in->parse_error.empty());
}

TEST(Protocol, ReceiveIsBoundedInTime) {
  const auto ep = endpoint("silent");
  link::Hub hub(ep);
  const auto t0 = std::chrono::steady_clock::now();
  auto in = hub.receive(link::Millis(200));
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(in.has_value());
  EXPECT_LT(waited, 2.0);
}

namespace {
link::Capabilities caps() {
  link::Capabilities c;
  c.role = wire::PARTICLES;
  c.adapter = "test";
  c.provides = {field::position};
  return c;
}

wire::Envelope fromOrchestrator(std::uint64_t step,
                                std::uint32_t version = wire::PROTOCOL_VERSION) {
  wire::Envelope e;
  e.mutable_header()->set_protocol_version(version);
  e.mutable_header()->set_run_id("run1");
  e.mutable_header()->set_step(step);
  return e;
}
}  // namespace

TEST(Protocol, WrongProtocolVersionIsRefusedAtHandshake) {
  // The adapter side gets a Welcome from an orchestrator speaking another version: its first
  // command is refused with a message naming both versions.
  const auto ep = endpoint("version");
  link::Hub hub(ep);
  link::ParticipantOptions o;
  o.endpoint = ep;
  o.name = "particles";
  link::Session session(o, caps());
  std::thread orch([&] {
    auto hello = hub.receive(link::Millis(5000));
    ASSERT_TRUE(hello && hello->envelope && hello->envelope->has_hello());
    EXPECT_EQ(hello->envelope->header().protocol_version(),
              static_cast<unsigned>(wire::PROTOCOL_VERSION));
    auto w = fromOrchestrator(0);
    w.mutable_welcome();
    hub.send(hello->peer, w);
    auto cmd = fromOrchestrator(1, 99);
    cmd.mutable_advance();
    hub.send(hello->peer, cmd);
  });
  session.handshake();
  try {
    session.nextCommand();
    FAIL() << "a command of protocol version 99 was accepted";
  } catch (const link::ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("99"), std::string::npos) << e.what();
  }
  orch.join();
}

TEST(Protocol, OrchestratorRefusesAParticipantOfAnotherVersion) {
  // Orchestrator side: a Hello with a wrong version is answered with Refused (checked in the
  // end-to-end tests through the real orchestrator); here: the Refused reaches the session as
  // a PeerError carrying the reason.
  const auto ep = endpoint("refused");
  link::Hub hub(ep);
  link::ParticipantOptions o;
  o.endpoint = ep;
  o.name = "particles";
  link::Session session(o, caps());
  std::thread orch([&] {
    auto hello = hub.receive(link::Millis(5000));
    ASSERT_TRUE(hello && hello->envelope);
    auto r = fromOrchestrator(0);
    r.mutable_refused()->set_reason("protocol version 1 but the orchestrator speaks version 2");
    hub.send(hello->peer, r);
  });
  try {
    session.handshake();
    FAIL() << "refusal not reported";
  } catch (const link::PeerError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol version"), std::string::npos);
  }
  orch.join();
}

TEST(Protocol, OutOfOrderStepIsRefused) {
  const auto ep = endpoint("order");
  link::Hub hub(ep);
  link::ParticipantOptions o;
  o.endpoint = ep;
  o.name = "particles";
  link::Session session(o, caps());
  std::thread orch([&] {
    auto hello = hub.receive(link::Millis(5000));
    ASSERT_TRUE(hello && hello->envelope);
    auto w = fromOrchestrator(0);
    w.mutable_welcome();
    hub.send(hello->peer, w);
    for (std::uint64_t s : {1u, 2u, 5u}) {  // 2 -> 5 skips steps
      auto c = fromOrchestrator(s);
      c.mutable_advance();
      hub.send(hello->peer, c);
    }
    // The session answers the bad step with an Error naming it.
    for (int i = 0; i < 50; ++i) {
      auto in = hub.receive(link::Millis(200));
      if (in && in->envelope && in->envelope->has_error()) {
        EXPECT_NE(in->envelope->error().message().find("out-of-order"), std::string::npos);
        return;
      }
    }
    ADD_FAILURE() << "no Error sent back for the out-of-order step";
  });
  session.handshake();
  EXPECT_EQ(session.nextCommand().header().step(), 1u);
  EXPECT_EQ(session.nextCommand().header().step(), 2u);
  EXPECT_THROW(session.nextCommand(), link::ProtocolError);
  orch.join();
}

// The adapters' own command line (CLI11): the flags the orchestrator passes, OpenFOAM's options
// left over in order, --help, and the usage when a required flag is missing.
TEST(ParticipantOptions, CommandLine) {
  auto parse = [](std::vector<std::string> args, std::vector<std::string>* rest) {
    args.insert(args.begin(), "adapter");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    return link::ParticipantOptions::parse(static_cast<int>(args.size()), argv.data(),
                                           "test adapter", rest);
  };
  std::vector<std::string> rest;
  const auto o =
      parse({"--endpoint", "ipc:///tmp/x", "-parallel", "--name", "fluid", "-case", "/tmp/case",
             "--run-id", "r1", "--heartbeat-ms", "250", "--command-timeout", "7"},
            &rest);
  ASSERT_TRUE(o);
  EXPECT_EQ(o->endpoint, "ipc:///tmp/x");
  EXPECT_EQ(o->name, "fluid");
  EXPECT_EQ(o->run_id, "r1");
  EXPECT_EQ(o->heartbeat_ms, 250);
  EXPECT_EQ(o->command_timeout_ms, 7000);
  EXPECT_EQ(rest, (std::vector<std::string>{"-parallel", "-case", "/tmp/case"}));
  const auto defaults = parse({"--endpoint", "e", "--name", "particles"}, nullptr);
  ASSERT_TRUE(defaults);
  EXPECT_EQ(defaults->heartbeat_ms, 500);
  EXPECT_EQ(defaults->command_timeout_ms, 600000);
  testing::internal::CaptureStdout();
  EXPECT_FALSE(parse({"--help"}, nullptr));
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("test adapter"), std::string::npos) << help;
  EXPECT_NE(help.find("--endpoint"), std::string::npos) << help;
  try {
    parse({"--endpoint", "e"}, nullptr);
    ADD_FAILURE() << "no --name accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--name PARTICIPANT"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse({"--endpoint", "e", "--name", "n", "--heartbeat-ms", "x"}, nullptr),
               std::runtime_error);
}

// The models' batch is bound by wire field name (models/include/cosim/models/parcels.h): every
// name is a wire field, vectors have 3 components, and each array lands in its own member.
TEST(ParcelFields, AreWireFieldsAndBindToTheirMembers) {
  const auto& known = field::all();
  models::ParcelArrays arrays;
  double tag = 1.0;
  for (const auto& f : models::kParcelFields) {
    EXPECT_NE(std::find(known.begin(), known.end(), f.name), known.end()) << f.name;
    const bool vector = std::string(f.name) == field::position ||
                        std::string(f.name) == field::velocity ||
                        std::string(f.name) == field::fluid_velocity ||
                        std::string(f.name) == field::pressure_gradient;
    EXPECT_EQ(field::components(f.name), vector ? 3u : 1u) << f.name;
    arrays.*f.arrays = std::vector<double>(1, tag++);
  }
  const models::ParcelBatch b = arrays.view();
  EXPECT_EQ(b.n, 1u);
  EXPECT_EQ(b.position[0], 1.0);
  EXPECT_EQ(b.radius[0], 3.0);
  EXPECT_EQ(b.fluid_density[0], 6.0);
  EXPECT_EQ(b.cell_size[0], 10.0);
  arrays.precursor_fraction.clear();  // a field the scene does not carry
  EXPECT_EQ(arrays.view().precursor_fraction, nullptr);
}

// take() moves a field out whole, whatever was done to the ids before (the LIGGGHTS adapter
// moves the ids out of a packet first), and leaves nothing of it behind.
TEST(Protocol, ParticleDataTakeMovesAFieldOutWhole) {
  link::ParticleData d;
  d.ids = {4, 5};
  d.field(field::fluid_velocity) = {1, 2, 3, 4, 5, 6};
  const auto ids = std::move(d.ids);
  EXPECT_EQ(d.take(field::fluid_velocity), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_FALSE(d.has(field::fluid_velocity));
  EXPECT_TRUE(d.take(field::drag_coefficient).empty());
  EXPECT_EQ(ids.size(), 2U);
}

TEST(Protocol, ParticleDataSelectedFromATemporaryMovesTheFieldsAsACopyWouldHoldThem) {
  link::ParticleData d;
  d.ids = {4, 5};
  d.field(field::fluid_velocity) = {1, 2, 3, 4, 5, 6};
  d.field(field::drag_coefficient) = {7, 8};
  const std::vector<std::string> names = {field::drag_coefficient, field::voidage};
  const link::ParticleData copied = d.select(names);
  const double* storage = d.get(field::drag_coefficient).data();
  const link::ParticleData moved = std::move(d).select(names);
  EXPECT_EQ(moved.ids, copied.ids);
  EXPECT_EQ(moved.names(), copied.names());
  EXPECT_EQ(moved.get(field::drag_coefficient), (std::vector<double>{7, 8}));
  EXPECT_EQ(moved.get(field::drag_coefficient).data(), storage);  // the same array, not a copy
  EXPECT_FALSE(moved.has(field::fluid_velocity));
}
