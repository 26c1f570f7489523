// Wire cost of one coupling step, in particles per second, for the packets of the plasma coating
// bed (the fields its plan negotiates; see `cosim validate scenarios/plasma-coating-bed`):
//   Pack/<packet>/N      ParticleData -> Envelope (FieldSet) -> bytes -> Envelope -> ParticleData
//   Exchange/<pair>/N    one request/reply over Hub (ROUTER) <-> Channel (DEALER) between two
//                        threads, each side packing and unpacking as the orchestrator and the
//                        participant session do; wall-clock time (the peer's work is included)
// bytes_per_particle is the size of the serialised envelope(s) divided by N; page_faults is the
// process's minor page faults per iteration (both threads).
//
// Heap: glibc starts with a 128 KiB mmap/trim threshold and raises it only after freeing a large
// mapped block, so a fresh process re-faults its packet buffers every iteration (5-6x slower) while
// a running orchestrator does not (0 minor faults per step measured on a 4,000-parcel coating bed).
// The thresholds are pinned high below so every benchmark measures that steady state whatever ran
// before it; page_faults shows it holds.
// Run: build/bin/cosim_coupling_bench (COSIM_BENCH_LARGE=1 for 2^20 and 10^7 particles too)
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cosim.pb.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_data.h"
#include "cosim/link/particle_wire.h"
#include "cosim/link/transport.h"

namespace {

namespace wire = cosim::wire;
namespace field = cosim::field;
using cosim::link::Millis;
using cosim::link::ParticleData;

using Fields = std::vector<std::string>;
// Particles -> orchestrator (Advanced.state).
const Fields kState = {field::position, field::velocity, field::radius, field::coating_mass};
// Orchestrator -> particles (Advance.terms).
const Fields kForcing = {field::drag_coefficient, field::fluid_velocity, field::explicit_force,
                         field::coating_increment};
// Orchestrator -> fluid (Sample.particles).
const Fields kSampleAt = {field::position, field::radius, field::velocity};
// Fluid -> orchestrator (Samples.at_particles).
const Fields kSamples = {field::fluid_velocity,  field::voidage,           field::fluid_density,
                         field::fluid_viscosity, field::pressure_gradient, field::cell_size};
// Orchestrator -> fluid (Advance.terms) and fluid -> orchestrator (Advanced.state).
const Fields kExchange = {field::drag_coefficient, field::transfer_coefficient};
const Fields kRemoved = {field::precursor_removed};

const bool kSteadyHeap = [] {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  return true;
}();

long minorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

void report(benchmark::State& state, std::size_t n, std::size_t bytes, long faults) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
  state.counters["bytes_per_particle"] = static_cast<double>(bytes) / static_cast<double>(n);
  state.counters["page_faults"] =
      benchmark::Counter(static_cast<double>(faults), benchmark::Counter::kAvgIterations);
}

enum class Body { sample, samples, advance, advanced };

// ids 1..n as LIGGGHTS numbers them; values are random doubles (every double is 8 bytes on the
// wire whatever it holds, so the values do not change the cost).
ParticleData makeData(std::size_t n, const Fields& names, std::uint64_t seed) {
  ParticleData d;
  d.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) d.ids[i] = static_cast<std::int64_t>(i + 1);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& name : names) {
    for (auto& x : d.field(name)) x = u(rng);
  }
  return d;
}

wire::Envelope envelope(Body body, const ParticleData& d, std::uint64_t step) {
  wire::Envelope e;
  auto* h = e.mutable_header();
  h->set_protocol_version(wire::PROTOCOL_VERSION);
  h->set_run_id("bench");
  h->set_participant("peer");
  h->set_step(step);
  h->set_time(1e-4 * static_cast<double>(step));
  switch (body) {
    case Body::sample:
      cosim::link::toWire(d, *e.mutable_sample()->mutable_particles());
      break;
    case Body::samples:
      cosim::link::toWire(d, *e.mutable_samples()->mutable_at_particles());
      break;
    case Body::advance: {
      auto* a = e.mutable_advance();
      a->set_dt(1e-4);
      a->set_substeps(10);
      cosim::link::toWire(d, *a->mutable_terms());
      break;
    }
    case Body::advanced: {
      auto* a = e.mutable_advanced();
      a->set_wall_seconds(0.02);
      cosim::link::toWire(d, *a->mutable_state());
      break;
    }
  }
  return e;
}

ParticleData unpack(const wire::Envelope& e) {
  switch (e.body_case()) {
    case wire::Envelope::kSample:
      return cosim::link::fromWire(e.sample().particles());
    case wire::Envelope::kSamples:
      return cosim::link::fromWire(e.samples().at_particles());
    case wire::Envelope::kAdvance:
      return cosim::link::fromWire(e.advance().terms());
    case wire::Envelope::kAdvanced:
      return cosim::link::fromWire(e.advanced().state());
    default:
      return {};
  }
}

// COSIM_BENCH_LARGE=1 adds 2^20 and 10^7 particles (a cluster-sized bed through one process: about
// 1.3 GB a message at 10^7, some 6 GB of memory at the peak; a few iterations each).
bool large() {
  const char* v = std::getenv("COSIM_BENCH_LARGE");
  return v != nullptr && std::string(v) != "0" && !std::string(v).empty();
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {1000, 4000, 16000, 65536}) b->Arg(n);
  if (large()) b->Arg(1 << 20)->Arg(10000000);
}

void tcpSizes(benchmark::internal::Benchmark* b) {
  for (int n : {4000, 65536}) b->Arg(n);
  if (large()) b->Arg(1 << 20)->Arg(10000000);
}

// ---- packing round trip ------------------------------------------------------------------------

void BM_Pack(benchmark::State& state, Body body, const Fields* fields) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ParticleData d = makeData(n, *fields, 1);
  std::size_t bytes = 0;
  std::uint64_t step = 0;
  const long faults0 = minorFaults();
  for (auto _ : state) {
    const wire::Envelope e = envelope(body, d, ++step);
    const std::string b = cosim::link::serialize(e);
    const wire::Envelope back = cosim::link::parse(b.data(), b.size());
    const ParticleData out = unpack(back);
    benchmark::DoNotOptimize(out.ids.data());
    bytes = b.size();
  }
  report(state, n, bytes, minorFaults() - faults0);
}

BENCHMARK_CAPTURE(BM_Pack, state, Body::advanced, &kState)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Pack, forcing, Body::advance, &kForcing)->Apply(sizes);

// ---- request/reply over the transport ----------------------------------------------------------

struct Pair {
  Body request;
  const Fields* request_fields;
  Body reply;
  const Fields* reply_fields;
};
// The three exchanges of a coating-bed step.
const Pair kParticleStep{Body::advance, &kForcing, Body::advanced, &kState};
const Pair kFluidSample{Body::sample, &kSampleAt, Body::samples, &kSamples};
const Pair kFluidStep{Body::advance, &kExchange, Body::advanced, &kRemoved};

std::string endpointFor(const std::string& transport) {
  static std::atomic<int> counter{0};
  if (transport.rfind("tcp", 0) == 0) return "tcp://127.0.0.1:*";
  return "ipc:///tmp/cosim-bench-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
         ".ipc";
}

void BM_Exchange(benchmark::State& state, const char* transport, Pair pair) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const ParticleData request = makeData(n, *pair.request_fields, 1);
  const ParticleData reply = makeData(n, *pair.reply_fields, 2);
  // "tcp_curve": the link of a tcp:// run, CurveZMQ with one issued client key.
  cosim::link::HubSecurity security;
  cosim::link::CurveClientKeys client;
  if (std::string(transport) == "tcp_curve") {
    security.server = cosim::link::newCurveKeyPair();
    client = {security.server.public_key, cosim::link::newCurveKeyPair()};
    security.clients.insert(client.own.public_key);
  }
  cosim::link::Hub hub(endpointFor(transport), security);
  const std::string endpoint = hub.endpoint();

  // The participant: unpack each command as the session does, answer with a packed reply.
  std::thread peer([&endpoint, &reply, &pair, &client] {
    cosim::link::Channel channel(endpoint, "peer", client);
    wire::Envelope hello;
    hello.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
    hello.mutable_hello()->set_adapter("bench");
    channel.send(hello);
    while (true) {
      auto cmd = channel.receive(Millis(10000));
      if (!cmd || cmd->has_shutdown()) return;
      const ParticleData in = unpack(*cmd);
      benchmark::DoNotOptimize(in.ids.data());
      channel.send(envelope(pair.reply, reply, cmd->header().step()));
    }
  });

  auto stop = [&] {
    wire::Envelope bye;
    bye.mutable_header()->set_protocol_version(wire::PROTOCOL_VERSION);
    bye.mutable_shutdown()->set_reason("done");
    try {
      hub.send("peer", bye);
    } catch (...) {
    }
    peer.join();
  };
  auto hello = hub.receive(Millis(10000));
  if (!hello || !hello->envelope || !hello->envelope->has_hello()) {
    state.SkipWithError("the peer thread did not connect");
    stop();
    if (endpoint.rfind("ipc://", 0) == 0) std::remove(endpoint.c_str() + 6);
    return;
  }

  std::uint64_t step = 0;
  const long faults0 = minorFaults();
  for (auto _ : state) {
    hub.send("peer", envelope(pair.request, request, ++step));
    auto in = hub.receive(Millis(10000));
    if (!in || !in->envelope) {
      state.SkipWithError("no reply from the peer thread");
      break;
    }
    const ParticleData back = unpack(*in->envelope);
    benchmark::DoNotOptimize(back.ids.data());
  }
  const long faults = minorFaults() - faults0;
  stop();
  // ZeroMQ leaves the socket file of a closed ipc:// endpoint behind.
  if (endpoint.rfind("ipc://", 0) == 0) std::remove(endpoint.c_str() + 6);

  const std::size_t bytes = cosim::link::serialize(envelope(pair.request, request, step)).size() +
                            cosim::link::serialize(envelope(pair.reply, reply, step)).size();
  report(state, n, bytes, faults);
}

BENCHMARK_CAPTURE(BM_Exchange, particles_ipc, "ipc", kParticleStep)->Apply(sizes)->UseRealTime();
BENCHMARK_CAPTURE(BM_Exchange, particles_tcp, "tcp", kParticleStep)->Apply(tcpSizes)->UseRealTime();
BENCHMARK_CAPTURE(BM_Exchange, particles_tcp_curve, "tcp_curve", kParticleStep)
    ->Apply(tcpSizes)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Exchange, fluid_sample_ipc, "ipc", kFluidSample)->Apply(sizes)->UseRealTime();
BENCHMARK_CAPTURE(BM_Exchange, fluid_advance_ipc, "ipc", kFluidStep)->Apply(sizes)->UseRealTime();

}  // namespace
