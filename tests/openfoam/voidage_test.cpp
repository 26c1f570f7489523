// Voidage from the satellite-point division: exact for parcels wholly inside cells, total
// parcel volume conserved for any placement (faces, walls, several cells).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <tuple>

#include "foam_harness.h"

namespace cosim::test {
namespace {

// The column case: 20 x 20 x 100 mm, 4 mm cubic cells (5 x 5 x 25).
constexpr double kCell = 0.004;
constexpr double kCellVolume = kCell * kCell * kCell;

FoamRunConfig columnConfig(const std::string& options) {
  FoamRunConfig cfg;
  cfg.substitute = {
      {"inlet_velocity", "0"}, {"inlet_precursor", "0"}, {"write_steps", "1"}, {"wall_U", "slip"}};
  cfg.options_yaml = options;
  cfg.send = {"voidage", "cell_size"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  return cfg;
}

double sphereVolume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

int cellIndex(double x, double y, double z) {
  const int i = static_cast<int>(x / kCell), j = static_cast<int>(y / kCell),
            k = static_cast<int>(z / kCell);
  return i + 5 * j + 25 * k;  // blockMesh numbering: x fastest, then y, then z
}

TEST(OpenFoamVoidage, ExactPerCellForParcelsWhollyInsideCells) {
  const double r = 0.7e-3;
  // Cell (i,j,k) gets (i + j + k) % 5 parcels at fixed spots at least r + 0.3 mm from its faces
  const double spots[4][3] = {{1.0e-3, 1.0e-3, 1.0e-3},
                              {3.0e-3, 3.0e-3, 1.0e-3},
                              {1.0e-3, 3.0e-3, 3.0e-3},
                              {3.0e-3, 1.0e-3, 3.0e-3}};
  std::vector<double> xyz;
  std::map<int, int> count;
  for (int k = 2; k < 12; ++k) {
    for (int j = 0; j < 5; ++j) {
      for (int i = 0; i < 5; ++i) {
        const int n = (i + j + k) % 5;
        for (int s = 0; s < std::min(n, 4); ++s) {
          xyz.insert(xyz.end(),
                     {i * kCell + spots[s][0], j * kCell + spots[s][1], k * kCell + spots[s][2]});
          ++count[i + 5 * j + 25 * k];
        }
      }
    }
  }
  FoamRun run(columnConfig("{min_voidage: 0.05, voidage_divisions: 3}"));
  const auto particles = makeParticles(xyz, r);
  const auto reply = run.sample(particles);
  ASSERT_TRUE(reply.lost.empty());
  const auto& eps = reply.at.get("voidage");
  const auto& size = reply.at.get("cell_size");
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const int c = cellIndex(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
    const double expected = 1.0 - count[c] * sphereVolume(r) / kCellVolume;
    EXPECT_NEAR(eps[p], expected, 1e-12) << "particle " << p + 1 << " in cell " << c;
    EXPECT_NEAR(size[p], kCell, 1e-12);
  }

  // The written field, cell by cell
  run.advance(1e-3, cosim::link::ParticleData{});
  const auto field = readLatestCellField(run.caseDir(), "voidage");
  ASSERT_EQ(field.size(), 625u);
  for (int c = 0; c < 625; ++c) {
    const double expected = 1.0 - count[c] * sphereVolume(r) / kCellVolume;
    EXPECT_NEAR(field[static_cast<std::size_t>(c)], expected, 1e-12) << "cell " << c;
  }
  EXPECT_EQ(run.shutdown(), 0);
}

TEST(OpenFoamVoidage, ConservesTotalParcelVolumeAnywhere) {
  // 400 parcels anywhere in the lower half: across faces, edges, corners, touching walls
  const double r = 0.9e-3;
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 53);
  };
  std::vector<double> xyz;
  for (int p = 0; p < 400; ++p) {
    xyz.insert(xyz.end(), {0.02 * uniform(), 0.02 * uniform(), 0.005 + 0.045 * uniform()});
  }
  for (const int divisions : {2, 4}) {
    FoamRun run(
        columnConfig("{min_voidage: 0.01, voidage_divisions: " + std::to_string(divisions) + "}"));
    const auto reply = run.sample(makeParticles(xyz, r));
    ASSERT_TRUE(reply.lost.empty());
    run.advance(1e-3, cosim::link::ParticleData{});
    const auto field = readLatestCellField(run.caseDir(), "voidage");
    double solid = 0;
    double minEps = 1;
    for (const double e : field) {
      solid += (1.0 - e) * kCellVolume;
      minEps = std::min(minEps, e);
    }
    ASSERT_GT(minEps, 0.01) << "the bound must not act in this test";
    const double total = 400 * sphereVolume(r);
    EXPECT_NEAR(solid, total, 1e-12 * total) << divisions << "^3 satellites";
    EXPECT_EQ(run.shutdown(), 0);
  }
}

TEST(OpenFoamVoidage, BoundedBelowByTheConfiguredMinimum) {
  // 5 x 5 x 5 (overlapping) parcels of r = 0.5 mm in one cell: more solid than the cell holds
  std::vector<double> xyz;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k)
        xyz.insert(xyz.end(), {0.5e-3 + i * 0.75e-3, 0.5e-3 + j * 0.75e-3, 0.0405 + k * 0.75e-3});
  const double phi = 125 * sphereVolume(0.5e-3) / kCellVolume;
  ASSERT_GT(phi, 0.65);
  FoamRun run(columnConfig("{min_voidage: 0.35}"));
  const auto reply = run.sample(makeParticles(xyz, 0.5e-3));
  for (const double e : reply.at.get("voidage")) EXPECT_DOUBLE_EQ(e, 0.35);
  EXPECT_EQ(run.shutdown(), 0);
}

}  // namespace
}  // namespace cosim::test
