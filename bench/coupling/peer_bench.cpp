// What the rank-to-rank data path (coupling.data_path: peer; docs/design.md section 5) costs per
// parcel and interval outside the solvers, for the coating bed's laws and fields with the
// overlapped scheme as it ships (scenarios/plasma-coating-bed with coupling.data_path=peer):
//   PeerInterval/parcels:N/shared:S
//       one interval between a ParticlePeer (this thread) and a FluidPeer (another thread) over
//       ipc://, with the Welcome the orchestrator gives each side and the scene's own laws
//       (ScenePeerTerms): the particles' terms and positions to the fluid, the fluid's removal
//       and the gas sampled ahead back, the laws over N parcels, the session's check of the
//       state it reports as ids only; S = 1: the per-parcel values through shared memory (what
//       two peers of one machine do, shared_arrays.h), S = 0: in the messages (across nodes).
//       Both solvers do nothing (the gas is a fixed field, the parcels stay where they are), so
//       the wall time is the path's own work: packing, the wire, unpacking, the laws, the checks.
// This is the coupling work per parcel (w) of a rank in bench/scaling's rank-to-rank model.
// Run: build/bin/cosim_peer_bench
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "cosim.pb.h"
#include "cosim/link/fields.h"
#include "cosim/link/peer_link.h"
#include "cosim/link/peer_terms.h"
#include "cosim/link/session.h"
#include "cosim/link/shared_arrays.h"
#include "participants.h"
#include "plan.h"
#include "scenario.h"

namespace {

namespace wire = cosim::wire;
namespace field = cosim::field;
namespace orch = cosim::orchestrator;
using cosim::link::ParticleData;

const bool kSteadyHeap =
    [] {  // as bench/coupling: the orchestrator's steady state, not a fresh heap
      mallopt(M_MMAP_THRESHOLD, 32 << 20);
      mallopt(M_TRIM_THRESHOLD, 256 << 20);
      return true;
    }();

// Parcels of 1.5 mm in the quick bed's lower 20 mm (36 mm square), some in its coating zone.
ParticleData bed(std::size_t n) {
  ParticleData p;
  p.ids.resize(n);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x, v;
  for (std::size_t i = 0; i < n; ++i) {
    p.ids[i] = static_cast<std::int64_t>(i + 1);
    x.insert(x.end(), {0.036 * u(rng) - 0.018, 0.036 * u(rng) - 0.018, 0.02 * u(rng)});
    v.insert(v.end(), {0.02 * u(rng) - 0.01, 0.02 * u(rng) - 0.01, 0.1 * u(rng) - 0.05});
  }
  p.put(field::position, std::move(x));
  p.put(field::velocity, std::move(v));
  p.field(field::radius).assign(n, 7.5e-4);
  p.field(field::coating_mass).assign(n, 1e-12);
  return p;
}

// A gas at rest but for a rising stream, of the bed's voidage; no parcel outside the mesh.
class FixedGas : public cosim::link::Solver {
 public:
  cosim::link::Capabilities capabilities() const override {
    return {wire::FLUID, "fixed-gas", {}, {}};
  }
  void configure(const wire::Welcome&) override {}
  void sample(const ParticleData& at, ParticleData& out, std::vector<std::int64_t>&) override {
    const std::size_t n = at.size();
    out.ids = at.ids;
    auto& u = out.field(field::fluid_velocity);
    u.assign(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) u[3 * i + 2] = 0.1 + 0.5 * static_cast<double>(i % 7);
    auto& e = out.field(field::voidage);
    e.resize(n);
    for (std::size_t i = 0; i < n; ++i) e[i] = 0.42 + 0.08 * static_cast<double>(i % 5);
    out.field(field::fluid_density).assign(n, 1.16);
    out.field(field::fluid_viscosity).assign(n, 1.76e-5);
    auto& g = out.field(field::pressure_gradient);
    g.assign(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) g[3 * i + 2] = -9000.0;
    out.field(field::cell_size).assign(n, 4e-3);
    out.field(field::precursor_fraction).assign(n, 1e-4);
  }
  // Every twentieth parcel took precursor (the coating zone's share of the bed, about 5 %).
  void advance(const wire::Advance&, const ParticleData& terms, wire::Advanced& out,
               ParticleData& state) override {
    out.mutable_fluid()->set_pressure_drop(250.0);
    state.ids = terms.ids;
    auto& rm = state.field(field::precursor_removed);
    rm.assign(terms.size(), 0.0);
    for (std::size_t i = 0; i < rm.size(); i += 20) rm[i] = 1e-15;
  }
};

// Parcels that stay where they are.
class StillParticles : public cosim::link::Solver {
 public:
  explicit StillParticles(ParticleData at) : at_(std::move(at)) {}
  cosim::link::Capabilities capabilities() const override {
    return {wire::PARTICLES, "still-particles", {}, {}};
  }
  void configure(const wire::Welcome&) override {}
  void advance(const wire::Advance&, const ParticleData&, wire::Advanced& out,
               ParticleData& state) override {
    out.mutable_particles()->set_particle_count(at_.size());
    state = at_;
  }

 private:
  ParticleData at_;
};

struct Ended : std::runtime_error {
  Ended() : std::runtime_error("bench over") {}
};

void BM_PeerInterval(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::filesystem::path scene =
      std::filesystem::path(COSIM_SOURCE_DIR) / "scenarios" / "plasma-coating-bed";
  const orch::Scenario sc = orch::loadScenario(scene, {"coupling.data_path=peer"});
  const auto models = orch::makeModels(sc);
  const orch::Plan plan = orch::makePlan(sc, models);
  if (!plan.peer) {
    state.SkipWithError("the scene does not take the peer path");
    return;
  }
  const std::string endpoint = "ipc:///tmp/cosim-peer-bench-" + std::to_string(::getpid()) + "-" +
                               std::to_string(n) + ".ipc";
  // /1: the per-parcel values through shared memory, as the peers of one machine (ipc://)
  const std::string shared =
      state.range(1) != 0 ? cosim::link::sharedArraysPrefix("bench-" + std::to_string(::getpid()))
                          : "";
  const orch::PeerKeys keys{endpoint, {}, {}, shared};
  const wire::Welcome fluid_welcome = orch::welcomeFor(
      sc, plan, sc.participants.at("fluid"), std::filesystem::temp_directory_path(), "", keys);
  const wire::Welcome particle_welcome = orch::welcomeFor(
      sc, plan, sc.participants.at("particles"), std::filesystem::temp_directory_path(), "", keys);

  cosim::link::FluidPeer fluid_peer(fluid_welcome.peer(), {"bench", "", "fluid"}, 10000,
                                    "ipc://unused");
  cosim::link::ScenePeerTerms laws;
  laws.configure(particle_welcome.peer());
  cosim::link::ParticlePeer particle_peer(particle_welcome.peer(), particle_welcome, laws,
                                          {"bench", "", "particles"}, 10000);
  const ParticleData parcels = bed(n);
  StillParticles particles(parcels);
  particle_peer.setState(parcels);

  wire::Advance cmd;
  cmd.set_dt(sc.coupling.dt);
  cmd.set_substeps(static_cast<int>(sc.coupling.dem_steps));
  std::atomic<bool> over{false};
  std::thread fluid_thread([&] {
    FixedGas gas;
    const cosim::link::PeerWatch watch = [&over] {
      if (over) throw Ended();
    };
    try {
      for (std::uint64_t k = 1;; ++k) {
        wire::Advanced out;
        fluid_peer.interval(gas, cmd, k, static_cast<double>(k) * cmd.dt(), out, watch);
      }
    } catch (const Ended&) {
    }
  });

  std::uint64_t step = 0;
  const cosim::link::PeerWatch nobody_gone = [] {};
  auto interval = [&] {
    ++step;
    wire::Advanced out;
    ParticleData now;
    particle_peer.interval(particles, cmd, step, static_cast<double>(step) * cmd.dt(), out, now,
                           nobody_gone);
    particle_peer.checkState(now);           // the session's check of a state sent as ids only
    particle_peer.setState(std::move(now));  // as the session does
    benchmark::DoNotOptimize(out.peer().ledger().passes_size());
  };
  // Untimed: the first interval samples the gas where the parcels are (nothing sampled ahead
  // yet) and every buffer meets its size for the first time.
  for (int k = 0; k < 3; ++k) interval();
  for (auto _ : state) interval();
  over = true;
  fluid_thread.join();
  std::remove(endpoint.c_str() + 6);  // ZeroMQ leaves the ipc:// socket file behind
  if (!shared.empty()) cosim::link::removeSharedArrays(shared);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
}

BENCHMARK(BM_PeerInterval)
    ->ArgNames({"parcels", "shared"})
    ->ArgsProduct({{1000, 4000, 16000, 65536}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
