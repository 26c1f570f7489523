// The PIV view of a run (piv_field.h, piv_command.h) and its comparison with measured profiles
// (piv_compare.h), on particles.h5 files and CSVs written here with values known by hand.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/piv_command.h"
#include "cosim/analysis/piv_compare.h"
#include "cosim/analysis/piv_field.h"
#include "cosim/analysis/report.h"
#include "cosim/link/fields.h"

namespace fs = std::filesystem;
using namespace cosim::analysis;

namespace {
fs::path freshDir(const std::string& name) {
  const fs::path p =
      fs::temp_directory_path() / ("cosim_piv_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

struct Parcel {
  double x, y, z, vz;
};

// One snapshot of parcels of radius 0.75 mm (diameter 1.5 mm) moving only vertically (and with
// a sideways velocity that must not matter).
cosim::link::ParticleData snapshot(const std::vector<Parcel>& parcels) {
  cosim::link::ParticleData p;
  for (std::size_t i = 0; i < parcels.size(); ++i)
    p.ids.push_back(static_cast<std::int64_t>(i + 1));
  auto& pos = p.field(cosim::field::position);
  auto& vel = p.field(cosim::field::velocity);
  auto& rad = p.field(cosim::field::radius);
  for (std::size_t i = 0; i < parcels.size(); ++i) {
    pos[3 * i] = parcels[i].x;
    pos[3 * i + 1] = parcels[i].y;
    pos[3 * i + 2] = parcels[i].z;
    vel[3 * i] = 7.0;
    vel[3 * i + 1] = -3.0;
    vel[3 * i + 2] = parcels[i].vz;
    rad[i] = 7.5e-4;
  }
  return p;
}

constexpr double kWall = -0.0125;  // front wall of a 25 mm deep vessel centred on y = 0

// Three snapshots (t = 0, 0.5, 0.6 s); the first is the discarded start-up.
//   A: in cell (ix 5, iz 13) of 10 mm cells (x from -50 mm, z from 0), 1 mm from the wall
//   B: same cell, 1.4 mm from the wall (< its 1.5 mm diameter: seen)
//   C: same cell, 1.6 mm from the wall (behind the first layer: not seen with the default depth)
//   D: cell (0, 14) then (0, 15), 0.8 mm from the wall
void writeHandRun(const fs::path& run) {
  ParticleRecorder rec(run, {cosim::field::position, cosim::field::velocity, cosim::field::radius},
                       RunIdentity{"hand", 5.0});
  rec.write(0.0, snapshot({{0.001, kWall + 0.001, 0.131, 100.0}}));
  rec.write(0.5, snapshot({{0.001, kWall + 0.001, 0.131, 2.0},
                           {0.009, kWall + 0.0014, 0.135, 1.0},
                           {0.009, kWall + 0.0016, 0.133, 50.0},
                           {-0.045, kWall + 0.0008, 0.149, -0.5}}));
  rec.write(0.6,
            snapshot({{0.002, kWall + 0.001, 0.132, 4.0}, {-0.045, kWall + 0.0008, 0.151, -1.5}}));
}

PivOptions handOptions() {
  PivOptions o;
  o.from = 0.5;
  o.wall_y = kWall;
  o.x_min = -0.05;
  o.x_max = 0.05;
  o.z_min = 0.0;
  o.z_max = 0.2;
  o.cell = 0.01;
  o.heights = {0.13, 0.15};
  return o;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(PivField, TimeAverageOfTheParcelsTouchingTheFrontWallAfterTheDiscardedStart) {
  const auto run = freshDir("hand");
  writeHandRun(run);
  const ParticleFile file(run / kParticlesFile);
  const PivResult r = pivField(file, handOptions());
  ASSERT_EQ(r.grid.nx, 10u);
  ASSERT_EQ(r.grid.nz, 20u);
  EXPECT_EQ(r.snapshots, 2u);  // t = 0 is discarded
  EXPECT_DOUBLE_EQ(r.first_time, 0.5);
  EXPECT_DOUBLE_EQ(r.last_time, 0.6);
  EXPECT_EQ(r.samples, 5u);  // A twice, B, D twice; not C (behind the first layer)
  // cell (5, 13): A (2 and 4 m/s) and B (1 m/s): 7/3
  EXPECT_EQ(r.grid.samples[13 * 10 + 5], 3u);
  EXPECT_NEAR(r.grid.mean(5, 13), 7.0 / 3.0, 1e-14);
  EXPECT_NEAR(r.grid.mean(0, 14), -0.5, 1e-14);
  EXPECT_NEAR(r.grid.mean(0, 15), -1.5, 1e-14);
  EXPECT_TRUE(std::isnan(r.grid.mean(5, 14)));
  EXPECT_NEAR(r.grid.xCentre(5), 0.005, 1e-15);
  EXPECT_NEAR(r.grid.zCentre(13), 0.135, 1e-15);
  // Profile at 0.13 m: the band 0.125 <= z < 0.135 holds A twice (2, 4), not B (z = 0.135).
  ASSERT_EQ(r.profiles.size(), 2u);
  EXPECT_EQ(r.profiles[0].samples[5], 2u);
  EXPECT_NEAR(r.profiles[0].vz[5], 3.0, 1e-14);
  EXPECT_TRUE(std::isnan(r.profiles[0].vz[0]));
  // Profile at 0.15 m: D at 0.149 and 0.151: (-0.5 - 1.5) / 2
  EXPECT_EQ(r.profiles[1].samples[0], 2u);
  EXPECT_NEAR(r.profiles[1].vz[0], -1.0, 1e-14);
}

TEST(PivField, AFixedDepthCountsTheParcelsBehindTheFirstLayerToo) {
  const auto run = freshDir("depth");
  writeHandRun(run);
  PivOptions o = handOptions();
  o.depth = 0.002;  // C (1.6 mm from the wall) is seen now
  const PivResult r = pivField(ParticleFile(run / kParticlesFile), o);
  EXPECT_EQ(r.grid.samples[13 * 10 + 5], 4u);
  EXPECT_NEAR(r.grid.mean(5, 13), (2.0 + 1.0 + 50.0 + 4.0) / 4.0, 1e-13);
  o.to = 0.55;  // the snapshot at 0.5 s alone: A (2), B (1), C (50)
  const PivResult w = pivField(ParticleFile(run / kParticlesFile), o);
  EXPECT_EQ(w.snapshots, 1u);
  EXPECT_NEAR(w.grid.mean(5, 13), (2.0 + 1.0 + 50.0) / 3.0, 1e-13);
  o.to = std::numeric_limits<double>::infinity();
  o.depth = 0.0009;  // only D (0.8 mm)
  const PivResult d = pivField(ParticleFile(run / kParticlesFile), o);
  EXPECT_EQ(d.samples, 2u);
}

TEST(PivField, APrescribedVelocityFieldIsReadBackOnTheGrid) {
  // Parcels on the wall at every cell centre of a 5 mm grid, with vz = g(x, z) and two
  // snapshots of opposite perturbation: every cell's time average is g at its centre.
  const auto run = freshDir("field");
  auto g = [](double x, double z) { return 1.5 * (1.0 - std::pow(x / 0.03, 2)) - 0.4 + 2.0 * z; };
  {
    ParticleRecorder rec(run,
                         {cosim::field::position, cosim::field::velocity, cosim::field::radius},
                         RunIdentity{"field", 5.0});
    for (int s = 0; s < 2; ++s) {
      std::vector<Parcel> ps;
      for (int iz = 0; iz < 8; ++iz)
        for (int ix = 0; ix < 12; ++ix) {
          const double x = -0.03 + (ix + 0.5) * 0.005, z = (iz + 0.5) * 0.005;
          ps.push_back({x, kWall + 0.0008, z, g(x, z) + (s == 0 ? 0.25 : -0.25)});
          ps.push_back({x, kWall + 0.01, z, 99.0});  // deep inside: never seen
        }
      rec.write(0.1 * s, snapshot(ps));
    }
  }
  PivOptions o;
  o.wall_y = kWall;
  o.x_min = -0.03;
  o.x_max = 0.03;
  o.z_max = 0.04;
  o.cell = 0.005;
  o.heights = {0.0125};
  const PivResult r = pivField(ParticleFile(run / kParticlesFile), o);
  writePiv(r, o, run / "piv");
  // grid.csv read back: x_m,z_m,vz_m_s,samples
  std::istringstream grid(readText(run / "piv" / "grid.csv"));
  std::string line;
  std::getline(grid, line);
  EXPECT_EQ(line, "x_m,z_m,vz_m_s,samples");
  int rows = 0;
  while (std::getline(grid, line)) {
    double x = 0, z = 0, v = 0;
    int n = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%d", &x, &z, &v, &n), 4) << line;
    EXPECT_EQ(n, 2) << line;
    EXPECT_NEAR(v, g(x, z), 1e-12) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 12 * 8);
  const auto prof = readProfileCsv(run / "piv" / "profiles.csv");
  ASSERT_EQ(prof.size(), 12u);
  for (const auto& p : prof) {
    EXPECT_DOUBLE_EQ(p.height, 0.0125);
    EXPECT_NEAR(p.vz, g(p.x, 0.0125), 1e-12);
  }
}

TEST(PivField, BadOptionsAndFilesSayWhatIsWrong) {
  PivOptions o = handOptions();
  o.cell = 0;
  EXPECT_THROW(PivAccumulator{o}, std::invalid_argument);
  o = handOptions();
  o.x_max = o.x_min;
  EXPECT_THROW(PivAccumulator{o}, std::invalid_argument);
  o = handOptions();
  o.heights = {0.3};
  try {
    PivAccumulator a(o);
    FAIL() << "a height above the grid was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0.3"), std::string::npos) << e.what();
  }
  const auto run = freshDir("late");
  writeHandRun(run);
  o = handOptions();
  o.from = 2.0;
  try {
    pivField(ParticleFile(run / kParticlesFile), o);
    FAIL() << "no snapshot after --from was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("from 0 to 0.6 s"), std::string::npos) << e.what();
  }
  o.from = 0.6;
  o.to = 0.5;
  EXPECT_THROW(PivAccumulator{o}, std::invalid_argument);
}

namespace {
// The hand run with the resolved scene a run of the spout would have: the PIV window and the
// discarded start as parameters.
void writeHandRunWithItsScene(const fs::path& run) {
  writeHandRun(run);
  std::ofstream(run / "scenario.resolved.yaml")
      << "# x.yaml as run\nname: x\nparameters:\n  piv_front_wall_y: -0.0125\n  piv_x_min: -0.05\n"
         "  piv_x_max: 0.05\n  piv_z_max: 0.2\n  piv_discard: 0.5\n";
}
}  // namespace

TEST(PivCommand, TakesTheWindowAndTheDiscardedTimeFromTheScene) {
  const auto run = freshDir("command");
  writeHandRunWithItsScene(run);
  PivCommandOptions c;
  c.run = run;
  c.cell = 0.01;
  c.plots = false;  // PivPlots draws them
  std::ostringstream out;
  EXPECT_EQ(runPivCommand(c, out), 0);
  EXPECT_FALSE(fs::exists(run / "piv" / "piv.png"));
  const auto prof = readProfileCsv(run / "piv" / "profiles.csv");
  ASSERT_EQ(prof.size(), 20u);  // 10 bins at 0.13 and 0.15 m
  EXPECT_NEAR(prof[5].vz, 3.0, 1e-14);
  EXPECT_NEAR(prof[10].vz, -1.0, 1e-14);
  EXPECT_TRUE(std::isnan(prof[0].vz));
  EXPECT_NE(out.str().find("2 snapshots from 0.5 to 0.6 s"), std::string::npos) << out.str();
  // Without the scene's window the command says which option to give.
  fs::remove(run / "scenario.resolved.yaml");
  try {
    runPivCommand(c, out);
    FAIL() << "a run without a PIV window was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--wall-y"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("holds no scenario.resolved.yaml"), std::string::npos)
        << e.what();
  }
}

namespace {
// Simulated: at 0.13 m vz = -0.5, 0.5, 1.5, 0.5, -0.5 at x = -20 .. 20 mm; at 0.15 m 2 and 0 at
// -10 and 10 mm (and no data at 0). Measured: four points at 0.13 m that the simulation covers,
// one 25 mm beyond its last point, one at 0.15 m.
void writeCompareFiles(const fs::path& dir) {
  std::ofstream(dir / "sim.csv") << "height_m,x_m,vz_m_s,samples\n"
                                    "0.13,-0.02,-0.5,3\n0.13,-0.01,0.5,3\n0.13,0,1.5,3\n"
                                    "0.13,0.01,0.5,3\n0.13,0.02,-0.5,3\n"
                                    "0.15,-0.01,2,1\n0.15,0,,0\n0.15,0.01,0,1\n";
  std::ofstream(dir / "measured.csv") << "# measured PIV, vertical velocity\n"
                                         "x_m, vz_m_s, height_m\n"
                                         "-0.015, 0, 0.13\n-0.005, 1.2, 0.13\n0, 1.0, 0.13\n"
                                         "0.025, -0.3, 0.13\n0.045, -0.2, 0.13\n0, 0.5, 0.15\n";
}
}  // namespace

TEST(PivCompare, MeanAbsoluteErrorPerProfileAndRegionByHand) {
  const auto dir = freshDir("compare");
  writeCompareFiles(dir);
  const auto r =
      comparePiv(readProfileCsv(dir / "sim.csv"), readProfileCsv(dir / "measured.csv"), {});
  ASSERT_EQ(r.profiles.size(), 2u);
  // 0.13 m: errors 0 (x -15 mm, interpolated 0), 0.2 (-5 mm: 1.0 against 1.2), 0.5 (0 mm),
  // 0.2 (25 mm: the last point's -0.5, within one spacing); 45 mm is beyond the simulation.
  const auto& a = r.profiles[0];
  EXPECT_DOUBLE_EQ(a.height, 0.13);
  EXPECT_EQ(a.all.points, 4u);
  EXPECT_NEAR(a.all.mae, 0.9 / 4, 1e-14);
  EXPECT_NEAR(a.core.mae, 0.7 / 2, 1e-14);   // measured vz > 0: -5 and 0 mm
  EXPECT_NEAR(a.sides.mae, 0.2 / 2, 1e-14);  // vz <= 0: -15 and 25 mm
  EXPECT_EQ(a.without_simulation, 1u);
  // 0.15 m: 1.0 interpolated between -10 and 10 mm (the empty bin skipped) against 0.5
  const auto& b = r.profiles[1];
  EXPECT_EQ(b.all.points, 1u);
  EXPECT_NEAR(b.all.mae, 0.5, 1e-14);
  EXPECT_NEAR(b.core.mae, 0.5, 1e-14);
  EXPECT_EQ(b.sides.points, 0u);
  EXPECT_NEAR(r.all.mae, 1.4 / 5, 1e-14);
  EXPECT_NEAR(r.core.mae, 1.2 / 3, 1e-14);
  EXPECT_NEAR(r.sides.mae, 0.2 / 2, 1e-14);
  // A core band instead of the sign: -20 .. 0 mm holds -15, -5 and 0 mm at 0.13 m and 0 at 0.15.
  PivCompareOptions band;
  band.core_band = std::make_pair(-0.02, 0.0);
  const auto c =
      comparePiv(readProfileCsv(dir / "sim.csv"), readProfileCsv(dir / "measured.csv"), band);
  EXPECT_NEAR(c.profiles[0].core.mae, 0.7 / 3, 1e-14);
  EXPECT_NEAR(c.profiles[0].sides.mae, 0.2, 1e-14);
  EXPECT_NEAR(c.core.mae, 1.2 / 4, 1e-14);
}

TEST(PivCompare, CommandWritesTheTableAndRefusesAHeightNotSimulated) {
  const auto dir = freshDir("compare_cmd");
  writeCompareFiles(dir);
  PivCompareCommandOptions c;
  c.simulated = dir / "sim.csv";
  c.measured = dir / "measured.csv";
  c.plots = false;  // PivPlots draws them
  std::ostringstream out;
  EXPECT_EQ(runPivCompareCommand(c, out), 0);
  const std::string csv = readText(dir / "comparison.csv");
  EXPECT_EQ(csv.rfind("height_m,region,points,mae_m_s,noise_mae_m_s\n", 0), 0u) << csv;
  // The value of a row that starts with `key`.
  auto value = [&](const std::string& key) {
    const auto at = csv.find("\n" + key);
    return at == std::string::npos ? -1.0 : std::stod(csv.substr(at + 1 + key.size()));
  };
  EXPECT_NEAR(value("0.13,core,2,"), 0.35, 1e-14) << csv;
  EXPECT_NEAR(value("0.13,sides,2,"), 0.1, 1e-14) << csv;
  EXPECT_NEAR(value("all,all,5,"), 0.28, 1e-14) << csv;
  std::ofstream(dir / "other.csv") << "height_m,x_m,vz_m_s\n0.14,0,1\n";
  c.measured = dir / "other.csv";
  try {
    runPivCompareCommand(c, out);
    FAIL() << "a measured height without a simulated profile was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("0.14"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--heights"), std::string::npos) << e.what();
  }
  // An output that is one of the inputs is refused; the measured file stays as it was.
  c.measured = dir / "measured.csv";
  const std::string before = readText(c.measured);
  c.output = c.measured;
  EXPECT_THROW(runPivCompareCommand(c, out), std::runtime_error);
  EXPECT_EQ(readText(c.measured), before);
  c.output.clear();
  // The run folder form asks for cosim piv first.
  c.simulated = dir;
  c.measured = dir / "measured.csv";
  EXPECT_THROW(runPivCompareCommand(c, out), std::runtime_error);
}

TEST(PivCompare, MalformedCsvNamesFileLineAndColumn) {
  const auto dir = freshDir("csv");
  std::ofstream(dir / "a.csv") << "height_m,x_m\n0.13,0\n";
  try {
    readProfileCsv(dir / "a.csv");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a.csv:1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("vz_m_s"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "b.csv") << "height_m,x_m,vz_m_s\n0.13,0,1\n0.13,zero,1\n";
  try {
    readProfileCsv(dir / "b.csv");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("b.csv:3 column x_m"), std::string::npos) << e.what();
  }
  // a PIV export in mm/s: 500 mm/s read as m/s would be faster than sound
  std::ofstream(dir / "mm.csv") << "height_m,x_m,vz_m_s\n0.13,0,120\n0.13,0.01,-500\n";
  try {
    readProfileCsv(dir / "mm.csv");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("mm.csv:3 column vz_m_s: -500 m/s is faster than sound"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(readProfileCsv(dir / "missing.csv"), std::runtime_error);
  try {
    readProfileCsv(dir);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

TEST(PivCompare, NothingToCompareIsAnErrorNotAnEmptyTable) {
  const std::vector<ProfilePoint> simulated = {{0.13, -0.01, 1.0}, {0.13, 0.01, 2.0}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // every measured velocity empty
  try {
    (void)comparePiv(simulated, {{0.13, 0.0, nan}, {0.13, 0.01, nan}}, {});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no point with a velocity"), std::string::npos)
        << e.what();
  }
  // measured x in millimetres: every point beyond the simulated bins (0.02 m of spacing)
  try {
    (void)comparePiv(simulated, {{0.13, -45.0, -0.6}, {0.13, 45.0, -0.6}}, {});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("none of the 2 measured points"), std::string::npos)
        << e.what();
  }
}

// Batch means by hand: ten snapshots with one parcel each in one bin, vz = 1, 2, ..., 10, in five
// blocks of two: block sums 3, 7, 11, 15, 19 of 2 samples, mean 5.5; the blocks' means 1.5 ..
// 9.5 have the standard deviation sqrt(40 / 4) = sqrt(10), so the mean's standard error is
// sqrt(10 / 5) = sqrt(2). A bin sampled in one block only has none. Unequal counts: block sums
// 1 (1 sample) and 8 (2), mean 3: sqrt(5/4 ((1 - 3)^2 + (8 - 6)^2)) / 3 = sqrt(10) / 3; in the
// accumulator, 1 (1 sample) and 3 + 4 (2), mean 8/3: sqrt(5/4 ((5/3)^2 + (5/3)^2)) / 3 =
// 5 sqrt(10) / 18.
TEST(PivField, ProfileStandardErrorsByBatchMeansByHand) {
  EXPECT_NEAR(batchMeansStandardError({3, 7, 11, 15, 19}, {2, 2, 2, 2, 2}), std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(batchMeansStandardError({1, 8, 0, 0, 0}, {1, 2, 0, 0, 0}), std::sqrt(10.0) / 3,
              1e-14);
  EXPECT_TRUE(std::isnan(batchMeansStandardError({5, 0}, {2, 0})));

  PivOptions o = handOptions();
  o.from = 0;
  o.blocks = 5;
  PivAccumulator acc(o);
  for (int s = 0; s < 10; ++s) {
    std::vector<Parcel> parcels{{0.001, kWall + 0.001, 0.131, s + 1.0}};  // bin x 5 at 0.13 m
    if (s == 3) parcels.push_back({-0.045, kWall + 0.001, 0.131, 9.0});   // bin x 0: one block
    if (s == 0) parcels.push_back({0.045, kWall + 0.001, 0.151, 1.0});    // bin x 9 at 0.15 m
    if (s == 2 || s == 3) parcels.push_back({0.045, kWall + 0.001, 0.151, s + 1.0});
    const auto snap = snapshot(parcels);
    acc.add(0.1 * s, snap.get(cosim::field::position), snap.get(cosim::field::velocity),
            snap.get(cosim::field::radius));
  }
  const auto& r = acc.result();
  EXPECT_EQ(r.blocks, 5u);
  EXPECT_NEAR(r.profiles[0].vz[5], 5.5, 1e-14);
  EXPECT_NEAR(r.profiles[0].stderr_vz[5], std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(r.profiles[0].vz[0], 9.0, 1e-14);
  EXPECT_TRUE(std::isnan(r.profiles[0].stderr_vz[0]));
  EXPECT_TRUE(std::isnan(r.profiles[0].stderr_vz[4]));  // no sample
  EXPECT_NEAR(r.profiles[1].vz[9], 8.0 / 3, 1e-14);
  EXPECT_NEAR(r.profiles[1].stderr_vz[9], 5 * std::sqrt(10.0) / 18, 1e-14);
}

// Independent samples of known spread: in each of 10 bins, 8 parcels per snapshot over 200
// snapshots with vz = 1 + N(0, 0.3^2); the mean's standard error is 0.3 / sqrt(1600) = 0.0075.
// Ten blocks give each bin's estimate from 9 degrees of freedom (a relative spread of about
// 24 %); over the 20 bins of the two heights the mean of se^2 / 0.0075^2 is 1 within about
// sqrt(2 / 180) = 11 % (one standard deviation; the seed is fixed).
TEST(PivField, StandardErrorsOfIndependentSamplesMatchSigmaOverRootN) {
  PivOptions o = handOptions();
  o.from = 0;
  PivAccumulator acc(o);
  std::mt19937_64 rng(20261204);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int s = 0; s < 200; ++s) {
    std::vector<Parcel> parcels;
    for (int ix = 0; ix < 10; ++ix)
      for (int k = 0; k < 8; ++k)
        for (const double z : {0.131, 0.151})
          parcels.push_back({-0.045 + 0.01 * ix, kWall + 0.001, z, 1.0 + noise(rng)});
    const auto snap = snapshot(parcels);
    acc.add(0.01 * s, snap.get(cosim::field::position), snap.get(cosim::field::velocity),
            snap.get(cosim::field::radius));
  }
  const auto& r = acc.result();
  double ratio = 0;
  int n = 0;
  for (const auto& p : r.profiles)
    for (std::size_t ix = 0; ix < p.x.size(); ++ix) {
      ASSERT_EQ(p.samples[ix], 1600u);
      ratio += p.stderr_vz[ix] * p.stderr_vz[ix] / (0.0075 * 0.0075);
      ++n;
    }
  EXPECT_NEAR(ratio / n, 1.0, 0.3);
}

// The comparison's noise floor by hand: simulated points at x = 0 and 10 mm with standard errors
// 0.3 and 0.4; measured at 0 mm (its own error 0.4 given) and at 5 mm (none given): at 0 mm
// sqrt(2/pi) sqrt(0.09 + 0.16) = 0.5 sqrt(2/pi); at 5 mm the interpolated error
// sqrt(0.25 * 0.09 + 0.25 * 0.16) = 0.25, so 0.25 sqrt(2/pi).
TEST(PivCompare, NoiseFloorFromTheStandardErrors) {
  const auto dir = freshDir("noise");
  std::ofstream(dir / "sim.csv") << "height_m,x_m,vz_m_s,samples,vz_stderr_m_s\n"
                                    "0.13,0,1.0,10,0.3\n0.13,0.01,2.0,10,0.4\n";
  std::ofstream(dir / "measured.csv") << "height_m,x_m,vz_m_s,vz_stderr_m_s\n"
                                         "0.13,0,1.5,0.4\n0.13,0.005,1.0,\n";
  const auto r =
      comparePiv(readProfileCsv(dir / "sim.csv"), readProfileCsv(dir / "measured.csv"), {});
  const double k = std::sqrt(2.0 / std::numbers::pi);
  EXPECT_NEAR(r.all.mae, (0.5 + 0.5) / 2, 1e-14);
  EXPECT_EQ(r.all.noise_points, 2u);
  EXPECT_NEAR(r.all.noise_mae, (0.5 * k + 0.25 * k) / 2, 1e-14);
  // without standard errors: no noise floor
  std::ofstream(dir / "plain.csv") << "height_m,x_m,vz_m_s\n0.13,0,1.0\n0.13,0.01,2.0\n";
  const auto plain =
      comparePiv(readProfileCsv(dir / "plain.csv"), readProfileCsv(dir / "measured.csv"), {});
  EXPECT_EQ(plain.all.noise_points, 0u);
  EXPECT_TRUE(std::isnan(plain.all.noise_mae));
  std::ofstream(dir / "negative.csv") << "height_m,x_m,vz_m_s,vz_stderr_m_s\n0.13,0,1.0,-0.1\n";
  EXPECT_THROW(readProfileCsv(dir / "negative.csv"), std::runtime_error);
  fs::remove_all(dir);
}

namespace {
bool isPng(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in && std::string(magic + 1, 3) == "PNG";
}
}  // namespace

// The figures: the field and profiles of `cosim piv`, the comparison of `cosim piv-compare`;
// without a python3 that has matplotlib the numbers still come out and the line says what to
// install.
TEST(PivPlots, FieldAndComparisonAsPngsOrWhatToInstall) {
  const auto run = freshDir("plots");
  writeHandRunWithItsScene(run);
  writeCompareFiles(run);
  PivCommandOptions field;
  field.run = run;
  field.cell = 0.01;
  PivCompareCommandOptions compare;
  compare.simulated = run / "sim.csv";
  compare.measured = run / "measured.csv";
  std::string why;
  if (findPython(why)) {
    std::ostringstream out;
    ASSERT_EQ(runPivCommand(field, out), 0);
    EXPECT_TRUE(isPng(run / "piv" / "piv.png")) << out.str();
    ASSERT_EQ(runPivCompareCommand(compare, out), 0);
    EXPECT_TRUE(isPng(run / "comparison.png")) << out.str();
    EXPECT_NE(out.str().find("plot: " + (run / "comparison.png").string()), std::string::npos)
        << out.str();
    // two runs compared: the legend names them; a name is text, not matplotlib's $math$ (an
    // unknown command in it would fail the drawing)
    PivCompareCommandOptions labelled = compare;
    labelled.output = run / "labelled.csv";
    labelled.simulated_label = "cg 5 $\\nosuchcommand$";
    labelled.measured_label = "cg 10";
    ASSERT_EQ(runPivCompareCommand(labelled, out), 0);
    EXPECT_TRUE(isPng(run / "labelled.png")) << out.str();
  }
  for (const std::string& bad : {std::string(), std::string("two\nlines"), std::string(41, 'x')}) {
    PivCompareCommandOptions labelled = compare;
    labelled.measured_label = bad;
    std::ostringstream out;
    EXPECT_THROW(runPivCompareCommand(labelled, out), std::runtime_error) << bad;
  }
  fs::remove(run / "piv" / "piv.png");
  fs::remove(run / "comparison.png");
  setenv("COSIM_PYTHON", "/nonexistent/python3", 1);
  std::ostringstream out;
  const int field_rc = runPivCommand(field, out);
  const int compare_rc = runPivCompareCommand(compare, out);
  unsetenv("COSIM_PYTHON");
  EXPECT_EQ(field_rc, 0);
  EXPECT_EQ(compare_rc, 0);
  EXPECT_TRUE(fs::exists(run / "piv" / "profiles.csv"));
  EXPECT_TRUE(fs::exists(run / "comparison.csv"));
  EXPECT_FALSE(fs::exists(run / "piv" / "piv.png"));
  EXPECT_NE(out.str().find("no plot: "), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("apt-get install python3-matplotlib"), std::string::npos) << out.str();
  fs::remove_all(run);
}
