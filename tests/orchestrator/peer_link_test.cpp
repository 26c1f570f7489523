// The peer link of coupling.data_path: peer (cosim/link/peer_link.h) between two test solvers in
// one process: one interval carries the samples, the terms and the removal the right way, and the
// link refuses what a stranger or a confused peer sends, naming it, and never waits forever.
#include "cosim/link/peer_link.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/session.h"
#include "cosim/link/shared_arrays.h"

using namespace cosim;
using namespace cosim::link;

namespace {

std::string endpoint(const std::string& tag) {
  return "ipc:///tmp/cosim-peer-test-" + tag + "-" + std::to_string(getpid()) + ".ipc";
}

// The names of this process's shared memory objects now in /dev/shm.
std::vector<std::string> sharedObjectsOf(const std::string& prefix) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator("/dev/shm"))
    if (e.path().filename().string().rfind(prefix.substr(1), 0) == 0)
      found.push_back(e.path().filename().string());
  return found;
}

// A gas of velocity (0, 0, u) everywhere; each parcel removes `k` of precursor per step.
class UniformGas : public Solver {
 public:
  Capabilities capabilities() const override { return {wire::FLUID, "uniform-gas", {}, {}}; }
  void configure(const wire::Welcome&) override {}
  void sample(const ParticleData& at, ParticleData& out, std::vector<std::int64_t>& lost) override {
    auto& u = out.field(field::fluid_velocity);
    for (std::size_t i = 0; i < at.size(); ++i) u[3 * i + 2] = 0.5;
    lost.push_back(at.ids.back());  // the last parcel is in no cell
    // the particles' Sample names their shared memory object until they have the answer
    if (!shared_prefix.empty()) sampled_from_shared = !sharedObjectsOf(shared_prefix).empty();
  }
  void advance(const wire::Advance& cmd, const ParticleData& terms, wire::Advanced& out,
               ParticleData& state) override {
    got_terms = terms;
    got_cmd_terms = fromWire(cmd.terms());
    out.mutable_fluid()->set_pressure_drop(42.0);
    state.ids = terms.ids;
    auto& rm = state.field(field::precursor_removed);
    for (std::size_t i = 0; i < terms.size(); ++i) rm[i] = i == 0 ? 1e-12 : 0.0;
  }
  ParticleData got_terms, got_cmd_terms;
  std::string shared_prefix;  // set: look for the peers' shared memory while sampling
  bool sampled_from_shared = false;
};

class RecordingParticles : public Solver {
 public:
  Capabilities capabilities() const override {
    return {wire::PARTICLES, "recording-particles", {}, {}};
  }
  void configure(const wire::Welcome&) override {}
  void advance(const wire::Advance& cmd, const ParticleData& terms, wire::Advanced&,
               ParticleData& state) override {
    got_terms = terms;
    got_cmd_terms = fromWire(cmd.terms());
    state = start;
  }
  ParticleData start, got_terms, got_cmd_terms;
};

// K = 1 for every parcel, the fluid velocity as forcing, the drag as the fluid's exchange term;
// the first parcel is in the zone.
class UnitDragLaws : public PeerTerms {
 public:
  void configure(const wire::PeerLink&) override {}
  Terms evaluate(const ParticleData& state, const ParticleData& samples,
                 const std::vector<char>& lost, double) override {
    Terms t;
    t.forcing.ids = state.ids;
    t.exchange.ids = state.ids;
    t.forcing.field(field::fluid_velocity) = samples.get(field::fluid_velocity);
    auto& k = t.forcing.field(field::drag_coefficient);
    for (std::size_t i = 0; i < state.size(); ++i) k[i] = lost[i] != 0 ? 0.0 : 1.0;
    t.exchange.field(field::drag_coefficient) = k;
    t.in_zone.assign(state.size(), 0);
    t.in_zone[0] = 1;
    return t;
  }
};

ParticleData parcels() {
  ParticleData p;
  p.ids = {7, 3, 9};
  p.field(field::position) = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  p.field(field::velocity).assign(9, 0.0);
  p.field(field::radius) = {1e-3, 1e-3, 1e-3};
  return p;
}

struct Link {
  wire::PeerLink fluid_side, particle_side;
  wire::Welcome particle_welcome;
  PeerIdentity fluid{"run1", "secret", "fluid"}, particles{"run1", "secret", "particles"};
  // shared: the per-parcel values through shared memory, as the orchestrator sets for ipc://
  explicit Link(const std::string& tag, bool shared = false) {
    fluid_side.set_bind(endpoint(tag));
    particle_side.set_connect(endpoint(tag));
    if (shared) {
      const std::string prefix = sharedArraysPrefix("test-" + tag + std::to_string(getpid()));
      fluid_side.set_shared_memory(prefix);
      particle_side.set_shared_memory(prefix);
    }
    for (const char* f : {field::position, field::radius}) particle_side.add_sample_state(f);
    particle_side.add_exchange(field::drag_coefficient);
    particle_side.set_coating(true);
    particle_side.set_zone_passes(true);
    particle_welcome.set_cfd_dt(1e-4);
    for (const char* f : {field::drag_coefficient, field::fluid_velocity, field::coating_increment})
      particle_welcome.add_receive(f);
  }
};

const PeerWatch kNobodyGone = [] {};

wire::Advance interval(double dt) {
  wire::Advance a;
  a.set_dt(dt);
  a.set_substeps(1);
  return a;
}

}  // namespace

class PeerLinkValues : public ::testing::TestWithParam<bool> {};  // through shared memory?

TEST_P(PeerLinkValues, OneIntervalCarriesSamplesTermsAndRemovalEachTheirWay) {
  Link l("one", GetParam());
  {
    FluidPeer fluid_peer(l.fluid_side, l.fluid, 10000, "ipc://unused");
    UnitDragLaws laws;
    ParticlePeer particle_peer(l.particle_side, l.particle_welcome, laws, l.particles, 10000);
    UniformGas fluid;
    fluid.shared_prefix = l.fluid_side.shared_memory();
    RecordingParticles particles;
    particles.start = parcels();
    particle_peer.setState(parcels());

    auto fluid_done = std::async(std::launch::async, [&] {
      wire::Advanced out;
      fluid_peer.interval(fluid, interval(1e-4), 1, 0.0, out, kNobodyGone);
      return out;
    });
    wire::Advance cmd = interval(1e-4);
    cmd.set_report_terms(true);
    wire::Advanced out;
    ParticleData state;
    particle_peer.interval(particles, cmd, 1, 0.0, out, state, kNobodyGone);
    const wire::Advanced fluid_out = fluid_done.get();
    EXPECT_EQ(fluid.sampled_from_shared, GetParam());

    // the particles' solver: the laws' forcing, in its terms and its Advance; nothing owed yet
    const auto& f = particles.got_terms;
    EXPECT_EQ(f.ids, (std::vector<std::int64_t>{7, 3, 9}));
    EXPECT_EQ(f.get(field::drag_coefficient), (std::vector<double>{1, 1, 0}));  // 9 in no cell
    EXPECT_EQ(f.get(field::coating_increment), (std::vector<double>{0, 0, 0}));
    EXPECT_EQ(f.get(field::fluid_velocity)[5], 0.5);
    EXPECT_EQ(particles.got_cmd_terms.get(field::coating_increment),
              f.get(field::coating_increment));
    EXPECT_FALSE(particles.got_cmd_terms.has(field::position));
    // the fluid's solver: the exchange terms, nothing else
    EXPECT_EQ(fluid.got_terms.names(), std::vector<std::string>{field::drag_coefficient});
    EXPECT_EQ(fluid.got_cmd_terms.get(field::drag_coefficient), (std::vector<double>{1, 1, 0}));
    EXPECT_EQ(fluid_out.fluid().pressure_drop(), 42.0);
    EXPECT_EQ(fluid_out.state().ids_size(), 0) << "per-parcel data went to the orchestrator";
    // the particles' account: the lost parcel, and their ledger's totals, no parcel by parcel
    const auto& acc = out.peer();
    EXPECT_EQ(acc.zone_ids_size(), 0);
    EXPECT_EQ(acc.removed().ids_size(), 0);
    EXPECT_EQ(std::vector<std::int64_t>(acc.lost_ids().begin(), acc.lost_ids().end()),
              std::vector<std::int64_t>{9});
    EXPECT_EQ(acc.ledger().removed(), 1e-12);  // parcel 7, the first, took 1e-12 (UniformGas)
    EXPECT_EQ(acc.ledger().credited(), 0.0);
    EXPECT_EQ(acc.ledger().credited_including_owed(), 1e-12);
    EXPECT_EQ(acc.ledger().passes_size(), 0);        // 7 entered the zone, and is still there
    EXPECT_EQ(acc.ledger().coating_outside(), 0.0);  // 7 took its 1e-12 inside its pass
    EXPECT_EQ(fromWire(acc.samples()).ids, (std::vector<std::int64_t>{7, 3, 9}));

    // The next interval pays parcel 7 what it took, from the particles' own ledger
    fluid_done = std::async(std::launch::async, [&] {
      wire::Advanced o;
      fluid_peer.interval(fluid, interval(1e-4), 2, 1e-4, o, kNobodyGone);
      return o;
    });
    particle_peer.setState(state);
    wire::Advanced out2;
    particle_peer.interval(particles, interval(1e-4), 2, 1e-4, out2, state, kNobodyGone);
    fluid_done.get();
    EXPECT_EQ(particles.got_terms.get(field::coating_increment),
              (std::vector<double>{1e-12, 0, 0}));
    EXPECT_EQ(out2.peer().ledger().removed(), 2e-12);
    EXPECT_EQ(out2.peer().ledger().credited(), 1e-12);
    EXPECT_EQ(out2.peer().ledger().credited_including_owed(), 2e-12);

    // The run's end: the last uptake paid, the open pass closed at the end of step 2
    wire::Advance flush;
    flush.set_pay_owed(true);
    flush.set_close_passes(true);
    const ParticleData last = particle_peer.zeroLengthTerms(flush);
    EXPECT_EQ(last.get(field::coating_increment), (std::vector<double>{1e-12, 0, 0}));
    wire::Advanced end;
    particle_peer.afterZeroLength(flush, 2, end);
    const auto& ledger = end.peer().ledger();
    EXPECT_EQ(ledger.credited(), 2e-12);
    ASSERT_EQ(ledger.passes_size(), 1);
    EXPECT_EQ(ledger.passes(0).parcel_id(), 7);
    EXPECT_EQ(ledger.passes(0).entry_time(), 0.0);
    EXPECT_EQ(ledger.passes(0).exit_time(), 2e-4);
    EXPECT_EQ(ledger.passes(0).coating(), 2e-12);
    EXPECT_TRUE(ledger.passes(0).at_start());
    EXPECT_EQ(ledger.passes(0).exit(), wire::ZonePass::RUN_END);
  }
  // the peers gone, none of their shared memory is left
  if (GetParam()) EXPECT_TRUE(sharedObjectsOf(l.fluid_side.shared_memory()).empty());
}

INSTANTIATE_TEST_SUITE_P(PeerLink, PeerLinkValues, ::testing::Values(false, true),
                         [](const auto& info) {
                           return info.param ? "ThroughSharedMemory" : "InTheMessages";
                         });

// A gas whose results name a parcel it was not sent: the particles refuse them, naming it.
class ConfusedGas : public UniformGas {
 public:
  void advance(const wire::Advance& cmd, const ParticleData& terms, wire::Advanced& out,
               ParticleData& state) override {
    UniformGas::advance(cmd, terms, out, state);
    state.ids = {3, 7, 99};  // 3 took nothing (not sent back); 99 was never sent
    state.field(field::precursor_removed) = {0.0, 1e-12, 2e-12};
  }
};

TEST(PeerLink, ResultsForAParcelNotSentAreRefusedNamingIt) {
  Link l("confused");
  FluidPeer fluid_peer(l.fluid_side, l.fluid, 10000, "ipc://unused");
  UnitDragLaws laws;
  ParticlePeer particle_peer(l.particle_side, l.particle_welcome, laws, l.particles, 10000);
  ConfusedGas fluid;
  RecordingParticles particles;
  particles.start = parcels();
  particle_peer.setState(parcels());
  auto fluid_done = std::async(std::launch::async, [&] {
    wire::Advanced out;
    fluid_peer.interval(fluid, interval(1e-4), 1, 0.0, out, kNobodyGone);
  });
  wire::Advanced out;
  ParticleData state;
  try {
    particle_peer.interval(particles, interval(1e-4), 1, 0.0, out, state, kNobodyGone);
    FAIL() << "results for a parcel never sent were taken";
  } catch (const ProtocolError& e) {
    // only the parcels that took any travel: 7 and 99, and 99 was not sent
    EXPECT_NE(std::string(e.what()).find("results for parcel 99, which it was not sent"),
              std::string::npos)
        << e.what();
  }
  fluid_done.get();
}

TEST(PeerLink, TheParticlesLedgerAndOpenPassesComeBackFromTheirCheckpointPart) {
  Link l("ledger");
  UnitDragLaws laws;
  ParticlePeer before(l.particle_side, l.particle_welcome, laws, l.particles, 10000);
  before.setState(parcels());
  // nothing happened yet: an empty ledger round-trips, and a damaged part is named
  ParticlePeer after(l.particle_side, l.particle_welcome, laws, l.particles, 10000);
  after.restoreLedger(before.ledgerBytes());
  EXPECT_EQ(after.ledgerBytes(), before.ledgerBytes());
  try {
    after.restoreLedger("\x0a\xff\xff");
    FAIL() << "a damaged peer_ledger.pb was read";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find(kPeerLedgerFile), std::string::npos) << e.what();
  }
}

TEST(PeerLink, AStrangersMessageIsDroppedAndAPeerOfAnotherStepIsRefused) {
  Link l("stranger");
  FluidPeer fluid_peer(l.fluid_side, l.fluid, 3000, "ipc://unused");
  UniformGas fluid;
  auto fluid_done = std::async(std::launch::async, [&] {
    wire::Advanced out;
    fluid_peer.interval(fluid, interval(1e-4), 5, 0.0, out, kNobodyGone);
  });
  Channel stranger(endpoint("stranger"));
  stranger.sendRaw("not a message at all");
  wire::Envelope wrong_token;
  wrong_token.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
  wrong_token.mutable_header()->set_run_id("run1");
  wrong_token.mutable_header()->set_token("guess");
  wrong_token.mutable_header()->set_step(5);
  toWire(parcels(), *wrong_token.mutable_sample()->mutable_particles());
  stranger.send(wrong_token);
  // one of the run, but for step 4
  wire::Envelope late = wrong_token;
  late.mutable_header()->set_token("secret");
  late.mutable_header()->set_step(4);
  Channel particles(endpoint("stranger"));
  particles.send(late);
  try {
    fluid_done.get();
    FAIL() << "a Sample of step 4 answered during step 5";
  } catch (const link::ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("a message for step 4 during step 5"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(stranger.receive(Millis(100))) << "the stranger got an answer";
}

TEST(PeerLink, ASilentPeerEndsTheWaitAndTheOrchestratorsDepartureToo) {
  Link l("silent");
  UnitDragLaws laws;
  RecordingParticles particles;
  {
    ParticlePeer particle_peer(l.particle_side, l.particle_welcome, laws, l.particles, 600);
    particle_peer.setState(parcels());
    wire::Advanced out;
    ParticleData state;
    try {
      particle_peer.interval(particles, interval(1e-4), 1, 0.0, out, state, kNobodyGone);
      FAIL() << "no fluid, and the interval returned";
    } catch (const link::TimeoutError& e) {
      EXPECT_NE(std::string(e.what()).find("the fluid participant sent nothing over the peer link"),
                std::string::npos)
          << e.what();
    }
  }
  ParticlePeer particle_peer(l.particle_side, l.particle_welcome, laws, l.particles, 60000);
  particle_peer.setState(parcels());
  wire::Advanced out;
  ParticleData state;
  const PeerWatch gone = [] { throw link::PeerError("the orchestrator is gone"); };
  EXPECT_THROW(particle_peer.interval(particles, interval(1e-4), 1, 0.0, out, state, gone),
               link::PeerError);
}

namespace {
std::vector<double> ramp(std::size_t n, double from) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = from + static_cast<double>(i);
  return v;
}
}  // namespace

TEST(SharedArrays, CarryValuesGrowPastTheFirstObjectAndUnlinkWhatThePeerHasHad) {
  const std::string prefix = sharedArraysPrefix("grow" + std::to_string(getpid()));
  SharedArrayWriter out(prefix, "fluid");
  SharedArrayReader in(prefix);
  // One message: a small array, then one larger than the first object (1 MiB), which moves the
  // writer to a second object while the first still holds the small one
  const auto small = ramp(3, 1.0), large = ramp(200000, 0.5);
  wire::SharedExtent a, b;
  ASSERT_TRUE(out.put(small.data(), small.size(), a)) << out.failure();
  ASSERT_TRUE(out.put(large.data(), large.size(), b)) << out.failure();
  EXPECT_NE(a.region(), b.region());
  EXPECT_EQ(a.region(), prefix + "-fluid-0");
  in.newMessage();
  EXPECT_EQ(std::vector<double>(in.at(a, 3), in.at(a, 3) + 3), small);
  EXPECT_EQ(in.at(b, large.size())[199999], 200000 - 0.5);
  EXPECT_EQ(sharedObjectsOf(prefix).size(), 2U);  // named until the peer has answered
  // The peer answered: the next message's first array unlinks the names and writes the newest
  // object again from its start
  out.answered();
  EXPECT_NE(out.at(b, large.size()), nullptr) << "what was put is there until the next put";
  wire::SharedExtent c;
  ASSERT_TRUE(out.put(small.data(), small.size(), c));
  EXPECT_TRUE(sharedObjectsOf(prefix).empty());
  EXPECT_EQ(out.at(a, 3), nullptr) << "the first object is gone";
  EXPECT_EQ(c.region(), b.region());
  EXPECT_EQ(c.offset(), 0U);
  in.newMessage();  // the reader drops the first object and keeps the one still written
  EXPECT_EQ(in.at(c, 3)[2], 3.0);
  EXPECT_THROW(in.at(a, 3), ProtocolError);  // unlinked and unmapped: gone
}

TEST(SharedArrays, TheReaderRefusesAnotherRunsObjectAndAnExtentPastTheEnd) {
  const std::string prefix = sharedArraysPrefix("refuse" + std::to_string(getpid()));
  SharedArrayWriter out(prefix, "particles");
  SharedArrayReader in(prefix);
  const auto v = ramp(10, 0.0);
  wire::SharedExtent e;
  ASSERT_TRUE(out.put(v.data(), v.size(), e));
  wire::SharedExtent other = e;
  other.set_region("/cosim-0-another-run-particles-0");
  try {
    in.at(other, 10);
    ADD_FAILURE() << "another run's object was opened";
  } catch (const ProtocolError& err) {
    EXPECT_NE(std::string(err.what()).find("not this run's"), std::string::npos) << err.what();
  }
  wire::SharedExtent past = e;
  past.set_offset(1U << 20);  // the first object's end
  EXPECT_THROW(in.at(past, 10), ProtocolError);
  wire::SharedExtent odd = e;
  odd.set_offset(3);
  EXPECT_THROW(in.at(odd, 1), ProtocolError);
}

TEST(SharedArrays, WithoutSharedMemoryTheValuesGoInTheMessageAndReadTheSame) {
  // A prefix no object can be made under (a folder inside the name): as a machine without
  // /dev/shm; the values travel in the message and the reader needs nothing of it
  SharedArrayWriter out("/no-such-folder/cosim", "fluid");
  ParticleData d = parcels();
  wire::FieldSet set;
  toWire(d, set, &out);
  EXPECT_FALSE(out.failure().empty());
  for (const auto& f : set.fields()) EXPECT_FALSE(f.has_shared()) << f.name();
  SharedArrayReader in("/no-such-folder/cosim");
  EXPECT_EQ(fromWire(set, &in).get(field::position), d.get(field::position));
  // and a message that says shared memory to a link without it is refused, naming the field
  const std::string prefix = sharedArraysPrefix("none" + std::to_string(getpid()));
  SharedArrayWriter shared(prefix, "fluid");
  toWire(d, set, &shared);
  try {
    fromWire(set);
    ADD_FAILURE() << "values in shared memory read without it";
  } catch (const ProtocolError& err) {
    EXPECT_NE(std::string(err.what()).find("'position'"), std::string::npos) << err.what();
  }
}

TEST(SharedArrays, WhatAKilledPeerLeftIsRemovedByTheRunsPrefixAndNothingElse) {
  const std::string prefix = sharedArraysPrefix("killed" + std::to_string(getpid()));
  const std::string neighbour = sharedArraysPrefix("killed" + std::to_string(getpid()) + "0");
  // a killed peer's object: named, and nobody left to unlink it
  const std::string left = prefix + "-fluid-3";
  const int fd = shm_open(left.c_str(), O_RDWR | O_CREAT | O_EXCL, S_IRUSR | S_IWUSR);
  ASSERT_GE(fd, 0);
  close(fd);
  SharedArrayWriter other(neighbour, "fluid");  // another run's, whose name extends this one's
  const auto v = ramp(4, 0.0);
  wire::SharedExtent e;
  ASSERT_TRUE(other.put(v.data(), v.size(), e));
  ASSERT_EQ(sharedObjectsOf(prefix + "-").size(), 1U);
  removeSharedArrays(prefix);
  EXPECT_TRUE(sharedObjectsOf(prefix + "-").empty());
  EXPECT_EQ(sharedObjectsOf(neighbour + "-").size(), 1U);
}
