// Precursor mass balance with a particle sink: over the run
//   inlet - outlet - (held at end - held at start) - removed by particles = 0
// to 1e-6 of the inlet (the adapter promises round-off), and the per-particle removals the
// orchestrator credits add up to what the cells lost.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "cosim/link/particle_wire.h"
#include "foam_harness.h"

namespace cosim::test {
namespace {

std::vector<double> sinkLattice() {
  std::vector<double> xyz;  // 5 x 5 x 10 parcels in the middle of the column
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        xyz.insert(xyz.end(), {2e-3 + 4e-3 * i, 2e-3 + 4e-3 * j, 0.03 + 3.1e-3 * k});
  return xyz;
}

struct Totals {
  double in = 0, out = 0, removed = 0, removedCells = 0, heldStart = 0, heldEnd = 0;
  double minY = 1, maxY = 0;
};

Totals runSink(double velocity, int ranks) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", std::to_string(velocity)},
                    {"inlet_precursor", "0.011"},
                    {"write_steps", "100000"},
                    {"wall_U", "noSlip"}};
  cfg.options_yaml = "{min_voidage: 0.35, schmidt: 1}";
  cfg.species = true;
  cfg.send = {"fluid_velocity", "voidage", "precursor_fraction", "precursor_removed"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient", "transfer_coefficient"};
  cfg.ranks = ranks;
  FoamRun run(cfg);

  const auto particles = makeParticles(sinkLattice(), 0.6e-3);
  Totals t;
  for (int step = 0; step < 80; ++step) {
    const auto s = run.sample(particles);
    EXPECT_TRUE(s.lost.empty());
    cosim::link::ParticleData terms;
    terms.ids = particles.ids;
    terms.field("drag_coefficient").assign(particles.size(), 2e-6);
    terms.field("transfer_coefficient").assign(particles.size(), 2e-7);
    const auto a = run.advance(2e-3, terms);
    const auto& sc = a.fluid().species();
    if (step == 0) t.heldStart = sc.precursor_held_start();
    t.heldEnd = sc.precursor_held();
    t.in += sc.precursor_in();
    t.out += sc.precursor_out();
    t.removedCells += sc.precursor_removed_cells();
    const auto state = cosim::link::fromWire(a.state());
    const auto& removed = state.get("precursor_removed");
    EXPECT_EQ(removed.size(), particles.size());
    t.removed += std::accumulate(removed.begin(), removed.end(), 0.0);
    t.minY = std::min(t.minY, sc.precursor_min());
    t.maxY = std::max(t.maxY, sc.precursor_max());
  }
  EXPECT_EQ(run.shutdown(), 0);
  return t;
}

void expectClosed(const Totals& t) {
  ASSERT_GT(t.in, 0);
  ASSERT_GT(t.removed, 0.01 * t.in) << "the sink must matter in this test";
  const double residual = t.in - t.out - (t.heldEnd - t.heldStart) - t.removed;
  EXPECT_LT(std::abs(residual), 1e-6 * t.in) << "in " << t.in << " out " << t.out << " held "
                                             << t.heldEnd - t.heldStart << " removed " << t.removed;
  EXPECT_NEAR(t.removed, t.removedCells, 1e-12 * t.in);
  EXPECT_GE(t.minY, -1e-12);
  EXPECT_LE(t.maxY, 0.011 + 1e-12);
  std::printf("in %.6e out %.6e accumulated %.6e removed %.6e residual/in %.2e\n", t.in, t.out,
              t.heldEnd - t.heldStart, t.removed,
              (t.in - t.out - (t.heldEnd - t.heldStart) - t.removed) / t.in);
}

TEST(OpenFoamSpecies, MassBalanceClosesWithParticleSink) { expectClosed(runSink(0.5, 1)); }

TEST(OpenFoamSpecies, MassBalanceClosesDecomposedOnTwoRanks) { expectClosed(runSink(0.5, 2)); }

}  // namespace
}  // namespace cosim::test
