// Particle location from step to step: parcels that move several cells between steps are found
// again (seeded walk), parcels outside the mesh are reported in lost_ids with zero samples and
// do not stop the run, and a decomposed run (mpirun -np 2, processor boundary at z = 50 mm)
// sees exactly what a serial one does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

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

// The samples of `inside` parcels at xyz (then parcels outside the mesh) on `ranks` processors
// (the column split n = `split` by decomposeParDict's simple method) against the serial run's,
// over two samples with a step between, the parcels exerting drag (different for each, strong
// enough to slow the gas in their cells by a tenth: terms that reached the wrong parcels would
// show). Decomposed, each processor works on the parcels that reach its box; the samples must
// be the serial run's to round-off (the processors' parts are added on the master), the gas
// after the step to its linear solvers' tolerance, and the same parcels lost.
void sampledAsOnOneRank(const std::vector<double>& xyz, std::size_t inside, int ranks,
                        const std::string& split, int mostInACell) {
  auto particles = makeParticles(xyz, kR);
  std::vector<std::int64_t> expectedLost;
  for (std::size_t p = inside; p < particles.size(); ++p) expectedLost.push_back(particles.ids[p]);
  struct Seen {
    std::vector<std::int64_t> lost;
    std::map<std::string, std::vector<double>> at;
  };
  auto seenOn = [&](int n) {
    FoamRunConfig cfg = columnConfig(n);
    cfg.edits = {{"system/decomposeParDict", "numberOfSubdomains 2;",
                  "numberOfSubdomains " + std::to_string(ranks) + ";"},
                 {"system/decomposeParDict", "n (1 1 2);", "n " + split + ";"}};
    FoamRun run(cfg);
    // an empty bed first: every processor takes part in the exchanges with nothing to send
    const auto none = run.sample(makeParticles({}, kR));
    EXPECT_TRUE(none.lost.empty());
    EXPECT_TRUE(none.at.get("voidage").empty());
    std::vector<Seen> steps;
    for (int step = 0; step < 2; ++step) {  // the second seeded by the first's cells
      const auto s = run.sample(particles);
      Seen seen{s.lost, {}};
      std::sort(seen.lost.begin(), seen.lost.end());
      for (const char* name : {"voidage", "cell_size", "fluid_velocity"})
        seen.at[name] = s.at.get(name);
      steps.push_back(std::move(seen));
      cosim::link::ParticleData terms;
      terms.ids = particles.ids;
      std::vector<double> K;
      for (std::size_t p = 0; p < particles.size(); ++p) K.push_back(1e-5 * double(1 + p % 7));
      terms.field("drag_coefficient") = K;
      run.advance(1e-3, terms);
    }
    EXPECT_EQ(run.shutdown(), 0);
    return steps;
  };
  const auto serial = seenOn(1);
  const auto decomposed = seenOn(ranks);
  ASSERT_EQ(serial.size(), decomposed.size());
  const double alone = 1 - 4.0 / 3.0 * std::numbers::pi * kR * kR * kR / (kCell * kCell * kCell);
  for (std::size_t step = 0; step < serial.size(); ++step) {
    EXPECT_EQ(serial[step].lost, expectedLost) << "step " << step;
    EXPECT_EQ(decomposed[step].lost, expectedLost) << "step " << step;
    for (const auto& [name, values] : serial[step].at) {
      // the gas after the step: its linear solvers leave 1e-11 m/s between the two runs, where
      // the drag moved it by 1e-4 m/s or more
      const double tolerance = step > 0 && name == "fluid_velocity" ? 1e-9 : 1e-12;
      const auto& other = decomposed[step].at.at(name);
      ASSERT_EQ(values.size(), other.size()) << name;
      for (std::size_t k = 0; k < values.size(); ++k)
        EXPECT_NEAR(other[k], values[k], tolerance * std::max(1.0, std::abs(values[k])))
            << name << " value " << k << " step " << step;
    }
    // At most mostInACell parcels' parts in a cell; none lost
    const auto& eps = decomposed[step].at.at("voidage");
    for (std::size_t p = 0; p < inside; ++p) {
      EXPECT_GE(eps[p], 1 - mostInACell * (1 - alone)) << "parcel " << p;
      EXPECT_LT(eps[p], 1.0) << "parcel " << p;
    }
    for (std::size_t p = inside; p < particles.size(); ++p) EXPECT_EQ(eps[p], 0.0) << p;
  }
}

constexpr double kMm = 1e-3;

// Two processors: the column's 625 cells go 313 to processor 0 and 312 to processor 1 by height,
// so the boundary runs along z = 48 mm, z = 52 mm and up the side faces of cells in the layer
// between. Parcels across the faces at 48 and 52 mm in every column of cells, across side faces
// in that layer, through the side wall, and outside the mesh within reach of one processor's
// box, of both and of neither.
TEST(OpenFoamParticleLocation, ParcelsAcrossTheProcessorBoundarySampledAsOnOneRank) {
  std::vector<double> xyz;
  for (double z : {48.3 * kMm, 51.7 * kMm})  // across the cell faces at 48 and 52 mm
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) xyz.insert(xyz.end(), {(i + 0.5) * kCell, (j + 0.5) * kCell, z});
  for (int i = 1; i < 5; ++i)  // across side faces of the layer between
    xyz.insert(xyz.end(), {i * kCell + 0.3 * kMm, 2 * kMm, 50 * kMm});
  xyz.insert(xyz.end(), {0.5 * kMm, 10 * kMm, 48.3 * kMm});  // ... and through the side wall
  const std::size_t inside = xyz.size() / 3;
  xyz.insert(xyz.end(), {-0.5 * kMm, 10 * kMm, 30 * kMm,    // outside; in reach of the lower box
                         -0.5 * kMm, 10 * kMm, 70 * kMm,    // ... of the upper box
                         -0.5 * kMm, 10 * kMm, 50 * kMm,    // ... of both
                         -9.0 * kMm, 10 * kMm, 50 * kMm});  // ... of neither
  sampledAsOnOneRank(xyz, inside, 2, "(1 1 2)", 3);
}

// Four processors side by side (x and y split in two): a cluster of 25 overlapping parcels at
// three heights where two, three or four of the processors meet, so that processors other than
// the master share parcels with each other.
TEST(OpenFoamParticleLocation, ParcelsWhereFourProcessorsMeetSampledAsOnOneRank) {
  std::vector<double> xyz;
  for (int k = 0; k < 3; ++k)
    for (double y : {7.7, 8.3, 10.0, 11.7, 12.3})
      for (double x : {7.7, 8.3, 10.0, 11.7, 12.3})
        // none exactly on a cell face (where two cells' claims are a tie either way)
        xyz.insert(xyz.end(), {x * kMm, y * kMm, (20 + 30 * k + (x + y) / 10 + 0.037) * kMm});
  const std::size_t inside = xyz.size() / 3;
  xyz.insert(xyz.end(), {10 * kMm, -0.5 * kMm, 50 * kMm,      // outside, in reach of two boxes
                         -0.5 * kMm, -0.5 * kMm, 50 * kMm});  // ... of one
  sampledAsOnOneRank(xyz, inside, 4, "(2 2 1)", 25);
}

}  // namespace
}  // namespace cosim::test
