// Particles per second of every law over a batch shaped like the paper's bed (65k parcels,
// cg 5, voidage 0.4..1, slip 0..3 m/s). Run: build/bin/cosim_models_bench
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "cosim/models/registry.h"

namespace {

using namespace cosim::models;

struct Bed : ParcelArrays {
  explicit Bed(std::size_t n) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
      position.insert(position.end(), {0.1 * u(rng) - 0.05, 0.1 * u(rng) - 0.05, 0.2 * u(rng)});
      velocity.insert(velocity.end(), {0.2 * u(rng) - 0.1, 0.2 * u(rng) - 0.1, u(rng) - 0.5});
      fluid_velocity.insert(fluid_velocity.end(), {0.1 * u(rng), 0.1 * u(rng), 3.0 * u(rng)});
      radius.push_back(7.5e-4);
      voidage.push_back(0.4 + 0.6 * u(rng));
      fluid_density.push_back(1.1 + 0.05 * u(rng));
      fluid_viscosity.push_back(1.8e-5);
      pressure_gradient.insert(pressure_gradient.end(), {0.0, 0.0, -8000.0 * u(rng)});
      cell_size.push_back(4e-3);
    }
  }
};

constexpr std::size_t kParcels = 65536;

SceneConstants scene() {
  SceneConstants c;
  c.cg = 5.0;
  c.min_voidage = 0.35;
  return c;
}

void runDrag(benchmark::State& state, const std::string& law, const Parameters& p) {
  const Bed bed(kParcels);
  auto model = Registry::instance().makeDrag(law, p);
  std::vector<double> K(kParcels);
  for (auto _ : state) {
    model->coefficients(bed.view(), scene(), K.data());
    benchmark::DoNotOptimize(K.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kParcels));
}

void BM_Drag(benchmark::State& state, const char* law) { runDrag(state, law, Parameters(law)); }

void BM_BeetstraFiltered(benchmark::State& state) {
  Parameters p("beetstra");
  p.setText("filtered", "true");
  p.set("particle_density", 1750.0);
  runDrag(state, "beetstra", p);
}

void BM_BeetstraFilteredReferenceGas(benchmark::State& state) {
  Parameters p("beetstra");
  p.setText("filtered", "true");
  p.set("particle_density", 1750.0);
  p.set("reference_fluid_density", 1.12);
  p.set("reference_fluid_viscosity", 1.8e-5);
  runDrag(state, "beetstra", p);
}

void BM_MassTransfer(benchmark::State& state, const char* law) {
  const Bed bed(kParcels);
  auto model = Registry::instance().makeMassTransfer(law, Parameters(law));
  std::vector<double> k(kParcels);
  for (auto _ : state) {
    model->transferCoefficients(bed.view(), scene(), k.data());
    benchmark::DoNotOptimize(k.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kParcels));
}

void BM_PressureGradient(benchmark::State& state) {
  const Bed bed(kParcels);
  auto model = Registry::instance().makeForce("pressure_gradient", Parameters("pg"));
  std::vector<double> f(3 * kParcels);
  for (auto _ : state) {
    model->addForces(bed.view(), scene(), f.data());
    benchmark::DoNotOptimize(f.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kParcels));
}

void BM_Zone(benchmark::State& state, const char* shape) {
  const Bed bed(kParcels);
  Parameters cyl("cyl");
  cyl.setText("shape", "cylinder");
  cyl.setList("base", {0, 0, 0});
  cyl.setList("axis", {0, 0, 1});
  cyl.set("radius", 0.02);
  cyl.set("length", 0.08);
  Parameters cone("cone");
  cone.setText("shape", "cone_frustum");
  cone.setList("base", {0, 0, 0.08});
  cone.setList("axis", {0, 0, 1});
  cone.set("length", 0.04);
  cone.set("base_radius", 0.02);
  cone.set("top_radius", 0.005);
  Parameters p(shape);
  const std::string s = shape;
  if (s == "cylinder") {
    p = cyl.without("shape", "cyl");
  } else if (s == "cone_frustum") {
    p = cone.without("shape", "cone");
  } else if (s == "box") {
    p.setList("min", {-0.02, -0.02, 0.0});
    p.setList("max", {0.02, 0.02, 0.1});
  } else if (s == "sphere") {
    p.setList("center", {0.0, 0.0, 0.05});
    p.set("radius", 0.03);
  } else {
    p.setChild("parts", {cyl, cone});
  }
  auto zone = Registry::instance().makeZone(shape, p);
  std::vector<double> mask(kParcels);
  for (auto _ : state) {
    zone->mask(bed.view(), mask.data());
    benchmark::DoNotOptimize(mask.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kParcels));
}

BENCHMARK_CAPTURE(BM_Drag, stokes, "stokes");
BENCHMARK_CAPTURE(BM_Drag, schiller_naumann, "schiller_naumann");
BENCHMARK_CAPTURE(BM_Drag, di_felice, "di_felice");
BENCHMARK_CAPTURE(BM_Drag, gidaspow, "gidaspow");
BENCHMARK_CAPTURE(BM_Drag, koch_hill, "koch_hill");
BENCHMARK_CAPTURE(BM_Drag, beetstra, "beetstra");
BENCHMARK(BM_BeetstraFiltered);
BENCHMARK(BM_BeetstraFilteredReferenceGas);
BENCHMARK(BM_PressureGradient);
BENCHMARK_CAPTURE(BM_MassTransfer, deen_gunn, "deen_gunn");
BENCHMARK_CAPTURE(BM_MassTransfer, gunn, "gunn");
BENCHMARK_CAPTURE(BM_MassTransfer, ranz_marshall, "ranz_marshall");
BENCHMARK_CAPTURE(BM_Zone, cylinder, "cylinder");
BENCHMARK_CAPTURE(BM_Zone, cone_frustum, "cone_frustum");
BENCHMARK_CAPTURE(BM_Zone, box, "box");
BENCHMARK_CAPTURE(BM_Zone, sphere, "sphere");
BENCHMARK_CAPTURE(BM_Zone, union_of_two, "union");

}  // namespace
