// Particle location from step to step: parcels that move several cells between steps are found
// again (seeded walk), parcels outside the mesh are reported in lost_ids with zero samples and
// do not stop the run, and a decomposed run (mpirun -np 2, processor boundary at z = 50 mm)
// sees exactly what a serial one does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cosim/link/particle_wire.h"
#include "cosim/link/session.h"
#include "foam_harness.h"

namespace cosim::test {
namespace {

constexpr double kCell = 0.004;
constexpr double kR = 0.8e-3;

// The column case with a slow upflow, sending voidage, cell size and gas velocity.
FoamRunConfig columnConfig(int ranks) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.1"},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.options_yaml = "{min_voidage: 0.05}";
  cfg.send = {"voidage", "cell_size", "fluid_velocity"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  cfg.ranks = ranks;
  return cfg;
}

void moveAndCheck(int ranks) {
  FoamRun run(columnConfig(ranks));

  // One parcel per column of cells (x, y), at the centre of cell k = 2 + (i + j) % 3: each
  // alone in its cell. Id 26 starts outside the mesh (x < 0).
  std::vector<double> xyz;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      xyz.insert(xyz.end(),
                 {(i + 0.5) * kCell, (j + 0.5) * kCell, (2 + (i + j) % 3 + 0.5) * kCell});
  xyz.insert(xyz.end(), {-0.01, 0.01, 0.05});
  auto particles = makeParticles(xyz, kR);
  const double alone = 1 - 4.0 / 3.0 * std::numbers::pi * kR * kR * kR / (kCell * kCell * kCell);

  for (int step = 0; step < 12; ++step) {
    const auto s = run.sample(particles);
    std::vector<std::int64_t> expectedLost{26};
    for (std::size_t p = 0; p < 25; ++p) {
      if (particles.get("position")[3 * p + 2] > 0.1) expectedLost.push_back(particles.ids[p]);
    }
    std::vector<std::int64_t> lost = s.lost;
    std::sort(lost.begin(), lost.end());
    std::sort(expectedLost.begin(), expectedLost.end());
    EXPECT_EQ(lost, expectedLost) << "step " << step;
    const auto& eps = s.at.get("voidage");
    const auto& size = s.at.get("cell_size");
    const auto& u = s.at.get("fluid_velocity");
    for (std::size_t p = 0; p < particles.size(); ++p) {
      const bool isLost = std::count(lost.begin(), lost.end(), particles.ids[p]) > 0;
      if (isLost) {
        EXPECT_EQ(eps[p], 0.0);
        EXPECT_EQ(size[p], 0.0);
        EXPECT_EQ(u[3 * p + 2], 0.0);
      } else {
        EXPECT_NEAR(eps[p], alone, 1e-12) << "particle " << particles.ids[p] << " step " << step;
        EXPECT_NEAR(size[p], kCell, 1e-12);
        EXPECT_GT(u[3 * p + 2], 0.05);  // the gas flows up everywhere
      }
    }
    run.advance(1e-3, cosim::link::ParticleData{});
    // Every parcel moves up two cells (8 mm) and sideways by one cell in x (wrapping)
    auto& pos = particles.field("position");
    for (std::size_t p = 0; p < 25; ++p) {
      pos[3 * p] = std::fmod(pos[3 * p] + kCell, 5 * kCell);
      pos[3 * p + 2] += 2 * kCell;
    }
  }
  EXPECT_EQ(run.shutdown(), 0);
}

TEST(OpenFoamParticleLocation, MovingParcelsFoundLostOnesReported) { moveAndCheck(1); }

// Coupling scheme overlapped: the fluid samples at position + velocity dt after its step,
// having located the parcels there on a helper thread during the step. Each of the 25 parcels
// moves one cell in +x over the step (velocity 40 m/s x 1e-4 s = 4 mm): the five of the last
// column leave the mesh (x > 20 mm), the others stay alone in their new cells. The samples must
// be exactly those of a plain Sample at the same positions.
TEST(OpenFoamParticleLocation, SamplesAheadAreThoseOfASampleWhereTheParcelsWillBe) {
  FoamRun run(columnConfig(1));
  const double dt = 1e-4;
  std::vector<double> xyz, v;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      xyz.insert(xyz.end(),
                 {(i + 0.5) * kCell, (j + 0.5) * kCell, (2 + (i + j) % 3 + 0.5) * kCell});
      v.insert(v.end(), {kCell / dt, 0.0, 0.0});
    }
  auto particles = makeParticles(xyz, kR);
  particles.field("velocity") = v;
  run.sample(particles);
  const auto advanced = run.advance(dt, cosim::link::ParticleData{}, &particles);
  ASSERT_TRUE(advanced.has_ahead());
  const auto ahead = cosim::link::fromWire(advanced.ahead().at_particles());
  std::vector<std::int64_t> lostAhead(advanced.ahead().lost_ids().begin(),
                                      advanced.ahead().lost_ids().end());
  std::sort(lostAhead.begin(), lostAhead.end());
  // ids 1..25 row by row: the last column is i = 4, ids 5, 10, 15, 20, 25
  EXPECT_EQ(lostAhead, (std::vector<std::int64_t>{5, 10, 15, 20, 25}));
  const double alone = 1 - 4.0 / 3.0 * std::numbers::pi * kR * kR * kR / (kCell * kCell * kCell);
  for (std::size_t p = 0; p < 25; ++p) {
    if (p % 5 == 4) continue;
    EXPECT_NEAR(ahead.get("voidage")[p], alone, 1e-12) << "parcel " << particles.ids[p];
  }
  // The same as a plain Sample at the predicted positions, bit for bit
  const auto plain = run.sample(cosim::link::predictedAt(particles, dt));
  for (const char* name : {"voidage", "cell_size", "fluid_velocity"})
    EXPECT_EQ(ahead.get(name), plain.at.get(name)) << name;
  std::vector<std::int64_t> lostPlain = plain.lost;
  std::sort(lostPlain.begin(), lostPlain.end());
  EXPECT_EQ(lostAhead, lostPlain);
  EXPECT_EQ(run.shutdown(), 0);
}

TEST(OpenFoamParticleLocation, SameOnTwoRanksAcrossTheProcessorBoundary) { moveAndCheck(2); }

}  // namespace
}  // namespace cosim::test
