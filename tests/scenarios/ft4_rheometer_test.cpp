// The FT4 rheometer scene with the real solvers at its tiny size (scenarios/ft4-rheometer/
// tiny.yaml, OpenFOAM + LIGGGHTS through the orchestrator): the blade rows of
// particles/ft4_blade.csv follow the prescribed motion, carry no force or torque while the
// blade waits above the bed, resist it once it is in the powder, and `cosim ft4 energy` gives
// the trapezoid sum of Eq. 11 over those rows, computed here independently. The gas domain is
// the vessel (an O-grid of the circle's area): fluidized, the bed's weight over the vessel's
// area is the pressure drop; at the scene's 4.7 L/min it is aerated, resting on the base.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/analysis/ft4_energy.h"
#include "cosim/analysis/report.h"
#include "cosim/link/fields.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {
struct Row {
  double t, h, f, m;
};

std::vector<Row> readRows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time_s,height_m,force_N,torque_Nm,averaged");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    for (auto& c : line)
      if (c == ',') c = ' ';
    std::istringstream r(line);
    Row x{};
    double averaged = 0;
    if (r >> x.t >> x.h >> x.f >> x.m >> averaged) {
      EXPECT_EQ(averaged, 1.0) << "t = " << x.t << ": a run that went through averages every row";
      rows.push_back(x);
    }
  }
  return rows;
}

double param(const Scenario& sc, const std::string& name) { return sc.parameters.at(name); }

// Mean of the run's pressure_drop column over the rows with from <= t <= to
double meanPressureDrop(const fs::path& run, double from, double to) {
  std::ifstream in(run / "timeseries.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
  const auto column = std::find(names.begin(), names.end(), "pressure_drop") - names.begin();
  EXPECT_LT(static_cast<std::size_t>(column), names.size()) << "no pressure_drop column";
  double sum = 0;
  int n = 0;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::istringstream r(line); std::getline(r, line, ',');) v.push_back(std::stod(line));
    if (v.size() == names.size() && v[0] >= from - 1e-9 && v[0] <= to + 1e-9) {
      sum += v[static_cast<std::size_t>(column)];
      ++n;
    }
  }
  EXPECT_GT(n, 10) << "too few rows between " << from << " and " << to << " s";
  return sum / n;
}

// Independent of the scene's expressions: the tiny size's 20 g of MCC (1750 kg/m3) as parcels of
// 3 mm, round(0.02 / (1750 pi/6 (3e-3)^3)) = 808 of them, in N2 (1.1231 kg/m3) in the vessel of
// radius 25 mm: (weight - buoyancy) over pi R^2
constexpr double kPi = std::numbers::pi;
constexpr double kParcels = 808, kDp = 3e-3, kRhoP = 1750, kRhoGas = 1.1231, kG = 9.81;
constexpr double kRadius = 0.025, kTinyHeight = 0.05;
double bedWeightOverArea() {
  return kParcels * kPi / 6 * kDp * kDp * kDp * (kRhoP - kRhoGas) * kG / (kPi * kRadius * kRadius);
}

// The run in `run` resumed from its checkpoint at t (quietly, with the same scene and sets).
RunResult resumeFrom(const fs::path& scene, const std::vector<std::string>& sets,
                     const fs::path& run, double t) {
  RunOptions r;
  r.quiet = true;
  r.resume = run;
  r.resume_from = t;
  return Coupler(loadScenario(scene, sets), r).run();
}
}  // namespace

TEST(Ft4RheometerTiny, BladeRowsAreZeroAboveTheBedResistingInItAndTheEnergyIsTheirIntegral) {
  const fs::path out = fs::temp_directory_path() / ("cosim-ft4-tiny-" + std::to_string(getpid()));
  fs::remove_all(out);
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/ft4-rheometer/tiny.yaml";
  const Scenario probe = loadScenario(scene);
  const double start = param(probe, "blade_start"), vz = param(probe, "blade_vz");
  const double aeration = param(probe, "aeration_time");
  const double radius = param(probe, "blade_radius"), helix = param(probe, "helix_deg");
  RunOptions o;
  o.quiet = true;
  o.output = out;
  RunResult r = Coupler(loadScenario(scene), o).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(static_cast<double>(r.final_state.ids.size()), param(probe, "n_grains"));
  const double end_time = probe.coupling.end_time;

  const auto rows = readRows(out / "particles" / "ft4_blade.csv");
  const double interval = param(probe, "output_interval");
  const double dem_dt = param(probe, "cfd_dt") / param(probe, "dem_steps");
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(std::floor(end_time / interval + 1e-9)));
  double sum_f_in = 0, sum_m_in = 0;
  int in_bed = 0;
  for (const auto& x : rows) {
    // the window's mean height: at rest until aeration_time, then falling at blade_vz (the
    // window ends at t and spans `interval`; heights are means over its DEM steps)
    const double t0 = x.t - interval;
    const double moving = std::max(0.0, x.t - std::max(t0, aeration));
    const double mean_travel =
        (moving > 0 ? (moving * (std::max(t0, aeration) - aeration) + 0.5 * moving * moving) : 0) /
        interval;
    // within 4 DEM steps of travel: the movers start, and ave/time samples, at whole steps
    // (measured: 1.5 steps, 2.6e-7 m)
    EXPECT_NEAR(x.h, start - vz * mean_travel, 4 * vz * dem_dt) << "t = " << x.t;
    if (x.t <= aeration + 1e-9) {
      // waiting 3 mm above the bed: exactly no contact
      EXPECT_EQ(x.f, 0.0) << "t = " << x.t;
      EXPECT_EQ(x.m, 0.0) << "t = " << x.t;
    }
    if (x.t > end_time - 0.1 - 1e-9) {  // the last 0.1 s: the blade is 3-4 mm deep
      sum_f_in += x.f;
      sum_m_in += x.m;
      ++in_bed;
    }
  }
  ASSERT_GT(in_bed, 5);

  // The air at 4.7 L/min (0.040 m/s over the vessel) is below minimum fluidization: over the
  // second half of the aeration the bed rests on the base and the gas carries only part of it
  // (measured: 34.2 Pa above the gas column, 34 % of the weight over the area)
  const double aerated = meanPressureDrop(out, aeration / 2, aeration);
  const double column = kRhoGas * kG * kTinyHeight;
  std::printf("aerated at 4.7 L/min: pressure drop %.2f Pa, (weight - buoyancy)/area %.2f Pa\n",
              aerated, bedWeightOverArea());
  EXPECT_GT(aerated - column, 0.2 * bedWeightOverArea());
  EXPECT_LT(aerated - column, 0.6 * bedWeightOverArea());
  EXPECT_GT(sum_f_in / in_bed, 0.0) << "the powder must push the descending blade up";
  EXPECT_GT(sum_m_in / in_bed, 0.0) << "the powder must resist the blade's rotation";

  // Eq. 11 by the trapezoid rule, independently of cosim's code
  double w = 0;
  const double lever = radius * std::tan(helix * std::numbers::pi / 180);
  for (std::size_t i = 1; i < rows.size(); ++i)
    w += 0.5 * (rows[i - 1].m / lever + rows[i - 1].f + rows[i].m / lever + rows[i].f) *
         (rows[i - 1].h - rows[i].h);
  EXPECT_GT(w, 0.0);
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/cosim ft4 energy " + out.string() +
                          " > " + (out / "energy.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream profile(out / "ft4_energy.csv");
  std::string line, last;
  while (std::getline(profile, line))
    if (!line.empty()) last = line;
  const double cosim_w = std::stod(last.substr(last.rfind(',') + 1));
  EXPECT_NEAR(cosim_w, w, 1e-12 * w);
  // its figure beside the profile, or the line that says why there is none
  std::ifstream said_file(out / "energy.txt");
  const std::string said((std::istreambuf_iterator<char>(said_file)), {});
  std::string why;
  if (cosim::analysis::findPython(why))
    EXPECT_TRUE(fs::exists(out / "ft4_energy.png")) << said;
  else
    EXPECT_NE(said.find("no plot: "), std::string::npos) << said;
  fs::remove_all(out);
}

// Fluidized (0.15 m/s, about 2 u_mf of these parcels, walls frictionless as in
// scenarios/fluidized-cylinder so that the vessel carries none of the weight, the blade parked
// 20 mm above the bed), the gas carries the whole bed over the whole gas domain: the time-averaged
// pressure drop is (weight - buoyancy) over the vessel's area plus the gas column. A gas domain
// larger than the vessel reads less (the box this scene had, at the same velocity: 70.0 Pa, 30 %
// low), one smaller (the polygon inscribed in the circle) more.
TEST(Ft4RheometerTiny, FluidizedTheBedRestsOnTheVesselsWholeArea) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-ft4-fluidized-" + std::to_string(getpid()));
  fs::remove_all(out);
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/ft4-rheometer/tiny.yaml";
  const double u0 = 0.15;
  const double lpm = u0 * kPi * kRadius * kRadius * 60000;
  RunOptions o;
  o.quiet = true;
  o.output = out;
  RunResult r =
      Coupler(loadScenario(scene, {"flow_lpm=" + std::to_string(lpm), "mu_wall=0", "blade_gap=0.02",
                                   "aeration_time=0.3", "end_time=0.3"}),
              o)
          .run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  ASSERT_EQ(static_cast<double>(r.final_state.ids.size()), kParcels);
  const double drop = meanPressureDrop(out, 0.1, 0.3);
  const double expected = bedWeightOverArea() + kRhoGas * kG * kTinyHeight;
  std::printf(
      "fluidized at %.2f L/min: pressure drop %.2f Pa over 0.1-0.3 s, (weight - "
      "buoyancy)/(pi R^2) + gas column %.2f Pa (%+.2f %%)\n",
      lpm, drop, expected, 100 * (drop - expected) / expected);
  EXPECT_NEAR(drop, expected, 0.025 * expected);
  fs::remove_all(out);
}

// Twice the tiny size's powder (40 g) in its 50 mm tall vessel: one pour of random loose packing
// cannot hold it (measured: 1,004 of the 1,617 parcels), and the run must stop before its first
// step with the counts and what to do, its recorded state kept; with more pours
// (fill_pours) every parcel is placed. round(0.04 / (1750 pi/6 (3e-3)^3)) = 1,617.
TEST(Ft4RheometerTiny, APowderOnePourCannotHoldIsRefusedOrPouredAgain) {
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/ft4-rheometer/tiny.yaml";
  const double want = std::round(0.04 / (kRhoP * kPi / 6 * kDp * kDp * kDp));
  ASSERT_EQ(want, 1617.0);
  const std::vector<std::string> sets = {"powder_mass=0.04", "coupling.end_time=0.002"};
  RunOptions o;
  o.quiet = true;
  {
    o.output = fs::temp_directory_path() / ("cosim-ft4-onepour-" + std::to_string(getpid()));
    fs::remove_all(o.output);
    RunResult r = Coupler(loadScenario(scene, sets), o).run();
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.message.find("checks.particle_count asks for 1617"), std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("could not place them all"), std::string::npos) << r.message;
    EXPECT_TRUE(fs::exists(o.output / "particles.h5"));
    fs::remove_all(o.output);
  }
  {
    o.output = fs::temp_directory_path() / ("cosim-ft4-pours-" + std::to_string(getpid()));
    fs::remove_all(o.output);
    auto more = sets;
    more.push_back("fill_pours=4");
    RunResult r = Coupler(loadScenario(scene, more), o).run();
    ASSERT_EQ(r.exit_code, 0) << r.message;
    EXPECT_EQ(static_cast<double>(r.final_state.ids.size()), want);
    fs::remove_all(o.output);
  }
}

// A resumed FT4 run replays the scene's script with its own flow control (the pours' `label`,
// `jump SELF`, `if`): LIGGGHTS allows `jump SELF` only in a script read as a file, so the
// adapter writes the rewritten script beside it (in.liggghts.resume) and runs that. Every FT4
// scene has such a jump (even one pour jumps over the others), so before this no FT4 run could
// be resumed. Here on two LIGGGHTS ranks (dem_ranks 2, as paper.yaml): run to 4 ms with a
// checkpoint at 2 ms, stop, resume from 2 ms to 4 ms: the same parcels at the same places as
// the run that went through (the restart gives the state back exactly, which the resume also
// checks before its first step).
TEST(Ft4RheometerTiny, ARunWithPoursResumesOnTwoRanks) {
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/ft4-rheometer/tiny.yaml";
  const std::vector<std::string> sets = {"fill_pours=2", "dem_ranks=2", "coupling.end_time=0.004",
                                         "checkpoint.interval=0.002", "checkpoint.keep=2"};
  RunOptions o;
  o.quiet = true;
  o.output = fs::temp_directory_path() / ("cosim-ft4-resume-" + std::to_string(getpid()));
  fs::remove_all(o.output);
  RunResult whole = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(whole.exit_code, 0) << whole.message;
  ASSERT_TRUE(fs::exists(o.output / "checkpoints/0.002"));
  RunResult resumed = resumeFrom(scene, sets, o.output, 0.002);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_TRUE(fs::exists(o.output / "particles/in.liggghts.resume"));
  ASSERT_EQ(resumed.final_state.ids, whole.final_state.ids);
  const auto& a = whole.final_state.get(cosim::field::position);
  const auto& b = resumed.final_state.get(cosim::field::position);
  ASSERT_EQ(a.size(), b.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  EXPECT_LT(worst, 1e-12) << "largest position difference [m]";
  fs::remove_all(o.output);
}

// A run resumed from a checkpoint between two blade rows (a Ctrl-C stop writes one at any step)
// starts LIGGGHTS' fix ave/time in the middle of an output interval; ave/time averages whole
// intervals only, so the row that ends it has no mean: before the `averaged` column it read as a
// blade at height 0 with no force, and `cosim ft4 energy` refused the run as a rising blade.
// Here: the blade descending from the start (no aeration), rows every 10 ms, a checkpoint at
// 15 ms; resumed from it, the row at 20 ms is written with averaged 0 and left out, and every
// other row equals the through run's (the resume gives the state back exactly).
TEST(Ft4RheometerTiny, AResumeBetweenTwoRowsLeavesOutTheIntervalItCut) {
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/ft4-rheometer/tiny.yaml";
  const std::vector<std::string> sets = {"aeration_time=0", "coupling.end_time=0.04",
                                         "checkpoint.interval=0.015", "checkpoint.keep=3"};
  RunOptions o;
  o.quiet = true;
  o.output = fs::temp_directory_path() / ("cosim-ft4-cut-" + std::to_string(getpid()));
  fs::remove_all(o.output);
  RunResult whole = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(whole.exit_code, 0) << whole.message;
  ASSERT_TRUE(fs::exists(o.output / "checkpoints/0.015"));
  const fs::path through = o.output.string() + "-through.csv";
  fs::copy_file(o.output / "particles/ft4_blade.csv", through,
                fs::copy_options::overwrite_existing);
  const auto expected = cosim::analysis::readBladeRows(through);
  ASSERT_EQ(expected.size(), 4u);  // 10, 20, 30, 40 ms

  RunResult resumed = resumeFrom(scene, sets, o.output, 0.015);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  std::vector<double> cut;
  const auto rows = cosim::analysis::readBladeRows(o.output / "particles/ft4_blade.csv", &cut);
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_NEAR(cut[0], 0.02, 1e-9);
  ASSERT_EQ(rows.size(), 3u);  // 10 ms from before the stop, 30 and 40 ms after the resume
  const std::size_t kept[] = {0, 2, 3};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& want = expected[kept[i]];
    EXPECT_NEAR(rows[i].time_s, want.time_s, 1e-12);
    EXPECT_NEAR(rows[i].height_m, want.height_m, 1e-12) << "t = " << want.time_s;
    EXPECT_EQ(rows[i].force_N, want.force_N) << "t = " << want.time_s;
    EXPECT_EQ(rows[i].torque_Nm, want.torque_Nm) << "t = " << want.time_s;
  }
  // the energy command reads the resumed run and names the row it left out
  const std::string cmd = std::string(COSIM_BINARY_DIR) + "/cosim ft4 energy " + o.output.string() +
                          " > " + (o.output / "energy.txt").string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream text(o.output / "energy.txt");
  const std::string said((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
  EXPECT_NE(said.find("left out 1 row(s) without a mean"), std::string::npos) << said;
  EXPECT_NE(said.find("t = 0.02 s"), std::string::npos) << said;
  fs::remove(through);
  fs::remove_all(o.output);
}
