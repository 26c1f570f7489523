// Particle location from step to step: parcels that move several cells between steps are found
// again (seeded walk), parcels outside the mesh are reported in lost_ids with zero samples and
// do not stop the run, and a decomposed run (mpirun -np 2, processor boundary at z = 50 mm)
// sees exactly what a serial one does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "foam_harness.h"

namespace cosim::test {
namespace {

constexpr double kCell = 0.004;
constexpr double kR = 0.8e-3;

void moveAndCheck(int ranks) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0.1"}, {"inlet_precursor", "0"},
                    {"write_steps", "100000"}, {"wall_U", "slip"}};
  cfg.options_yaml = "{min_voidage: 0.05}";
  cfg.send = {"voidage", "cell_size", "fluid_velocity"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  cfg.ranks = ranks;
  FoamRun run(cfg);

  // One parcel per column of cells (x, y), at the centre of cell k = 2 + (i + j) % 3: each
  // alone in its cell. Id 26 starts outside the mesh (x < 0).
  std::vector<double> xyz;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      xyz.insert(xyz.end(), {(i + 0.5) * kCell, (j + 0.5) * kCell, (2 + (i + j) % 3 + 0.5) * kCell});
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

TEST(OpenFoamParticleLocation, SameOnTwoRanksAcrossTheProcessorBoundary) { moveAndCheck(2); }

}  // namespace
}  // namespace cosim::test
