// Throughput of the recorder and the per-snapshot analytics on a paper-size bed.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/histogram.h"
#include "cosim/analysis/long_time.h"
#include "cosim/analysis/normality_test.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/link/fields.h"

using namespace cosim::analysis;

namespace {
std::vector<double> coating(std::size_t n) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> d(1e-9, 1e-10);
  std::vector<double> m(n);
  for (auto& x : m) x = d(rng);
  return m;
}

cosim::link::ParticleData bed(std::size_t n) {
  cosim::link::ParticleData p;
  p.ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.ids[i] = static_cast<std::int64_t>(i + 1);
  p.field(cosim::field::position);
  p.field(cosim::field::velocity);
  p.field(cosim::field::radius);
  p.field(cosim::field::coating_mass) = coating(n);
  return p;
}
}  // namespace

static void RecorderSnapshot(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto dir =
      std::filesystem::temp_directory_path() / ("cosim_bench_rec_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  ParticleRecorder rec(dir,
                       {cosim::field::position, cosim::field::velocity, cosim::field::radius,
                        cosim::field::coating_mass},
                       {"bench", 1.0});
  const auto p = bed(n);
  double t = 0;
  for (auto _ : state) rec.write(t += 0.01, p);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
  std::filesystem::remove_all(dir);
}
BENCHMARK(RecorderSnapshot)->Arg(5000)->Arg(65000)->Unit(benchmark::kMillisecond);

static void Statistics(benchmark::State& state) {
  const auto m = coating(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(coatingStatistics(1.0, m));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(Statistics)->Arg(65000);

static void HistogramFreedmanDiaconis(benchmark::State& state) {
  const auto m = coating(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(histogram(m));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(HistogramFreedmanDiaconis)->Arg(65000);

static void NormalityK2(benchmark::State& state) {
  const auto m = coating(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(dagostinoPearson(m));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(NormalityK2)->Arg(65000);

// The long-time model's batch: 65,000 parcels carried over `state.range(0)` intervals of 0.1 s
// between 48 compartments (6 rings x 8 layers) whose moves hold 40 recorded gains each. A 60 min
// batch is 36,000 intervals: the time per interval times 36,000 is its wall time.
static void LongTimeBatch(benchmark::State& state) {
  const int k = 48;
  const std::size_t n = 65000;
  CoatingDatabase db;
  db.grid.rings = 6;
  db.grid.layers = 8;
  db.interval = 0.1;
  db.times = {0.0, 0.1, 0.2};
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> st(0, k - 1);
  for (std::size_t j = 0; j < n; ++j) db.ids.push_back(static_cast<std::int64_t>(j + 1));
  db.state.assign(3, std::vector<int>(n));
  db.coating.assign(3, std::vector<double>(n, 0.0));
  for (auto& s : db.state)
    for (auto& x : s) x = st(rng);
  LongTimeModel m;
  m.states = k;
  m.interval = 0.1;
  m.P.assign(k * k, 0.0);
  m.gains.assign(k * k, {});
  m.departures.assign(k, 100);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      m.P[a * k + b] = (a == b ? 0.5 : 0.5 / (k - 1));
      for (int g = 0; g < 40; ++g) m.gains[a * k + b].push_back(a % 6 == 0 ? 1e-12 * g : 0.0);
    }
  for (auto _ : state) {
    auto pr = predictLongTime(m, db, {0.2 + 0.1 * static_cast<double>(state.range(0))}, 1);
    benchmark::DoNotOptimize(pr.final_coating.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0) * static_cast<std::int64_t>(n));
}
BENCHMARK(LongTimeBatch)->Arg(100)->Unit(benchmark::kMillisecond);
