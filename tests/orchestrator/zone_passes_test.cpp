// Zone passes (zone_passes.h, docs/analysis.md): the recorder on hand-made membership sequences,
// then whole runs with the analytic adapters: particles falling through two slabs of a coating
// zone, whose passes are known from the exact trajectory, and a run resumed from a checkpoint in
// the middle of passes, whose zone_passes.csv must equal the uninterrupted run's byte for byte.
#include "zone_passes.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "cosim/analysis/zone_pass_file.h"
#include "cosim/link/fields.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;
using analysis::ZonePass;
using Exit = ZonePass::Exit;

namespace {

fs::path freshFolder(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("cosim-zone-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  return p;
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

link::ParticleData removed(const std::vector<std::int64_t>& ids, const std::vector<double>& m) {
  link::ParticleData d;
  d.ids = ids;
  d.field(field::precursor_removed) = m;
  return d;
}

}  // namespace

TEST(ZonePassRecorder, FollowsTheMembershipStepByStep) {
  const fs::path dir = freshFolder("recorder");
  fs::create_directories(dir);
  ZonePassRecorder r;
  r.start(dir);
  const std::vector<std::int64_t> ids = {5, 3, 9, 7};
  // t = 0: 3 and 9 in the zone (at the start); each removes 1 kg over the step.
  r.update(0.0, ids, {0, 1, 1, 0});
  r.credit(removed(ids, {0, 1, 1, 0}));
  // t = 1: 3 left, 5 entered, 9 stays.
  r.update(1.0, ids, {1, 0, 1, 0});
  r.credit(removed(ids, {2, 0, 4, 0}));
  // t = 2: 9 is deleted at the end of the step (with its pass open); 3 enters again.
  r.update(2.0, ids, {1, 1, 1, 0});
  r.credit(removed(ids, {0.5, 0.25, 8, 0}));
  r.leave({9}, 3.0);
  const std::vector<std::int64_t> after = {5, 3, 7};
  r.update(3.0, after, {0, 1, 0});
  r.credit(removed(after, {0, 0.125, 0}));
  EXPECT_EQ(r.state().open.size(), 1u);  // parcel 3 since t = 2
  EXPECT_EQ(r.state().open.at(3).entry_time, 2.0);
  EXPECT_EQ(r.state().open.at(3).coating, 0.375);
  r.close(4.0);
  EXPECT_EQ(r.coatingOutsidePasses(), 0.0);
  EXPECT_EQ(r.state().rows, 4u);

  EXPECT_EQ(text(dir / "zone_passes.csv"),
            "parcel_id,entry_time,exit_time,coating_kg,entry,exit\n"
            "3,0,1,1,at_start,left\n"
            "9,0,3,13,at_start,deleted\n"
            "5,1,3,2.5,entered,left\n"
            "3,2,4,0.375,entered,run_end\n");

  // Coating credited to a parcel in no pass is counted (0 by design in a run).
  r.credit(removed({7}, {1e-9}));
  EXPECT_EQ(r.coatingOutsidePasses(), 1e-9);
  fs::remove_all(dir);
}

namespace {

// Particles falling from rest in still gas through a coating zone of two horizontal slabs,
// z in [10, 12] mm and [2, 4] mm, Stokes drag: z(t) = z0 - v_t (t - tau (1 - exp(-t/tau))) with
// tau = rho_p d^2 / (18 mu) = 0.01 s and v_t = g tau. The domain ends at z = 3 mm: particles are
// deleted in the lower slab. One starts inside the upper slab, one is still in it when the run
// ends, one never reaches the zone.
constexpr double kTau = 0.01, kG = 9.81, kDt = 1e-3, kEnd = 0.2, kBottom = 0.003;
const std::vector<double> kZ0 = {0.011, 0.013, 0.015, 0.02, 0.03, 0.035};

std::string fallingScene() {
  const double mu = 1.8e-5, rho = 2500.0;
  const double d = std::sqrt(kTau * 18.0 * mu / rho);
  std::string particles;
  for (std::size_t i = 0; i < kZ0.size(); ++i) {
    particles += "        - { id: " + std::to_string(i + 1) + ", position: [" +
                 std::to_string(0.001 * static_cast<double>(i)) + ", 0, " +
                 analysis::formatShortest(kZ0[i]) +
                 "], radius: " + analysis::formatShortest(d / 2) + " }\n";
  }
  return R"(name: falling-through-zone
participants:
  fluid:
    adapter: analytic-fluid
    options: { velocity: [0, 0, 0], density: 1.2, viscosity: 1.8e-5, precursor_fraction: 0.01,
               pressure_gradient: none }
  particles:
    adapter: free-particles
    options:
      density: 2500
      domain_min: [-1, -1, 0.003]
      domain_max: [1, 1, 1]
      particles:
)" + particles +
         R"(coupling: { dt: 1.0e-3, dem_steps: 1, end_time: 0.2 }
constants: { cg: 1, gravity: [0, 0, -9.81] }
models:
  drag: { law: stokes }
  mass_transfer: { law: ranz_marshall }
  coating_zone:
    shape: union
    parts:
      - { shape: box, min: [-1, -1, 0.010], max: [1, 1, 0.012] }
      - { shape: box, min: [-1, -1, 0.002], max: [1, 1, 0.004] }
output: { interval: 0.01 }
)";
}

double fallHeight(double z0, double t) {
  return z0 - kG * kTau * (t - kTau * (-std::expm1(-t / kTau)));
}
bool inZone(double z) { return (z >= 0.010 && z <= 0.012) || (z >= 0.002 && z <= 0.004); }

// The passes the exact trajectories give, by the recorder's convention: membership at the start
// of each step, a pass closes at the start of the first step outside, a deleted particle's at the
// end of the step it left the domain in, the rest at the run's end.
std::vector<ZonePass> expectedPasses(double& margin) {
  std::vector<ZonePass> out;
  margin = 1.0;
  const auto steps = static_cast<int>(std::lround(kEnd / kDt));
  for (std::size_t i = 0; i < kZ0.size(); ++i) {
    const auto id = static_cast<std::int64_t>(i + 1);
    std::optional<ZonePass> open;
    bool deleted = false;
    for (int k = 0; k <= steps && !deleted; ++k) {
      const double t = k * kDt, z = fallHeight(kZ0[i], t);
      for (double edge : {0.002, kBottom, 0.004, 0.010, 0.012})
        margin = std::min(margin, std::fabs(z - edge));
      if (k > 0 && z < kBottom) {
        deleted = true;
        if (open) {
          open->exit_time = t;
          open->exit = Exit::deleted;
          out.push_back(*open);
          open.reset();
        }
        break;
      }
      if (k == steps) break;
      if (inZone(z) && !open) open = ZonePass{id, t, 0, 0, k == 0, Exit::left};
      if (!inZone(z) && open) {
        open->exit_time = t;
        out.push_back(*open);
        open.reset();
      }
    }
    if (open) {
      open->exit_time = kEnd;
      open->exit = Exit::run_end;
      out.push_back(*open);
    }
  }
  return out;
}

}  // namespace

TEST(ZonePasses, FallingParticlesPassTheZoneWhenTheirExactTrajectorySays) {
  const fs::path dir = freshFolder("falling");
  fs::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << fallingScene();
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  RunResult r = Coupler(loadScenario(dir / "scene.yaml"), o).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;

  double margin = 0;
  auto expected = expectedPasses(margin);
  ASSERT_GT(margin, 1e-8) << "a step lands on a slab edge: move a particle";
  auto passes = analysis::readZonePasses(r.folder / analysis::kZonePassesFile);
  auto byParcel = [](std::vector<ZonePass>& v) {
    std::stable_sort(v.begin(), v.end(), [](const ZonePass& a, const ZonePass& b) {
      return a.parcel_id != b.parcel_id ? a.parcel_id < b.parcel_id : a.entry_time < b.entry_time;
    });
  };
  byParcel(passes);
  byParcel(expected);
  ASSERT_EQ(passes.size(), expected.size());
  // Parcels 1-4: upper slab then lower slab (deleted in it), parcel 1 from the start; parcel 5
  // enters the upper slab shortly before the end; parcel 6 never reaches the zone.
  ASSERT_EQ(expected.size(), 9u);
  for (std::size_t i = 0; i < passes.size(); ++i) {
    SCOPED_TRACE("pass " + std::to_string(i) + " of parcel " + std::to_string(passes[i].parcel_id));
    EXPECT_EQ(passes[i].parcel_id, expected[i].parcel_id);
    EXPECT_NEAR(passes[i].entry_time, expected[i].entry_time, 1e-12);
    EXPECT_NEAR(passes[i].exit_time, expected[i].exit_time, 1e-12);
    EXPECT_EQ(passes[i].at_start, expected[i].at_start);
    EXPECT_EQ(passes[i].exit, expected[i].exit);
    EXPECT_GT(passes[i].coating, 0.0) << "every step in the zone takes precursor";
  }
  // Parcel 3 crosses the upper slab (2 mm) at 98 % of its terminal velocity and more: it takes
  // about 2 mm / v_t = 20.4 ms, counted in whole steps.
  ASSERT_EQ(passes[4].parcel_id, 3);
  EXPECT_NEAR(passes[4].duration(), 0.002 / (kG * kTau), 1.5 * kDt);

  // Coating accrues only in the zone: each parcel's coating is the sum of its passes', and the
  // parcel that never entered has none.
  std::map<std::int64_t, double> inPasses;
  for (const auto& p : passes) inPasses[p.parcel_id] += p.coating;
  const auto& m = r.final_state.get(field::coating_mass);
  ASSERT_EQ(r.final_state.ids, (std::vector<std::int64_t>{5, 6}));
  EXPECT_NEAR(m[0], inPasses.at(5), 1e-12 * inPasses.at(5));
  EXPECT_EQ(m[1], 0.0);
  EXPECT_EQ(inPasses.count(6), 0u);
  fs::remove_all(dir);
}

TEST(ZonePasses, AResumedRunWritesTheSameFileAsTheUninterruptedOne) {
  const fs::path dir = freshFolder("resume");
  fs::create_directories(dir);
  std::ofstream(dir / "scene.yaml") << fallingScene();
  const std::vector<std::string> sets = {"checkpoint.interval=0.05", "checkpoint.keep=10"};
  RunOptions o;
  o.quiet = true;
  o.output = dir / "full";
  RunResult full = Coupler(loadScenario(dir / "scene.yaml", sets), o).run();
  ASSERT_EQ(full.exit_code, 0) << full.message;
  // At the checkpoint at 0.1 s parcel 4 is in the upper slab: an open pass crosses the restart.
  const auto saved = readCoupledState(dir / "full/checkpoints/0.1");
  ASSERT_TRUE(saved.zone_passes);
  EXPECT_EQ(saved.zone_passes->open.count(4), 1u);
  EXPECT_GT(saved.zone_passes->rows, 0u);

  // As after a kill: the folder as the full run left it, its newer checkpoints gone.
  fs::copy(dir / "full", dir / "cut", fs::copy_options::recursive);
  fs::remove_all(dir / "cut/checkpoints/0.15");
  fs::remove_all(dir / "cut/checkpoints/0.2");
  ASSERT_NE(text(dir / "cut/zone_passes.csv").find(",run_end"), std::string::npos);
  RunOptions ro;
  ro.quiet = true;
  ro.resume = dir / "cut";
  RunResult resumed = Coupler(loadScenario(dir / "scene.yaml", sets), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_EQ(text(dir / "cut/zone_passes.csv"), text(dir / "full/zone_passes.csv"));

  // A finished run made longer continues its passes: the rows closed at its old end are dropped.
  RunOptions lo;
  lo.quiet = true;
  lo.output = dir / "long";
  const std::vector<std::string> longer = {"checkpoint.interval=0.05", "checkpoint.keep=10",
                                           "coupling.end_time=0.3"};
  ASSERT_EQ(Coupler(loadScenario(dir / "scene.yaml", longer), lo).run().exit_code, 0);
  RunOptions eo;
  eo.quiet = true;
  eo.resume = dir / "full";
  ASSERT_EQ(Coupler(loadScenario(dir / "scene.yaml", longer), eo).run().exit_code, 0);
  EXPECT_EQ(text(dir / "full/zone_passes.csv"), text(dir / "long/zone_passes.csv"));
  fs::remove_all(dir);
}

TEST(ZonePasses, AreNotRecordedWithoutACoatingZone) {
  const fs::path dir = freshFolder("nozone");
  fs::create_directories(dir);
  std::string scene = fallingScene();
  scene = scene.substr(0, scene.find("  coating_zone:")) + "output: { interval: 0.01 }\n";
  std::ofstream(dir / "scene.yaml") << scene;
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  RunResult r = Coupler(loadScenario(dir / "scene.yaml", {"coupling.end_time=0.01"}), o).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_FALSE(fs::exists(r.folder / analysis::kZonePassesFile));
  fs::remove_all(dir);
}
