// Stability checks and monitors against hand-computed values.
#include "stability.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "cosim/link/fields.h"
#include "coupler.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(Stability, RayleighTimeOfThePapersGrains) {
  // docs/physics.md section 7: r = 0.75 mm, E = 5e6 Pa, nu = 0.3, rho = 1750 -> t_R ~ 7.7e-5 s.
  // By hand: G = 5e6/2.6 = 1.9231e6; pi * 7.5e-4 * sqrt(1750/1.9231e6) / 0.92553 = 7.681e-5.
  EXPECT_NEAR(rayleighTime(0.75e-3, 1750, 5e6, 0.3), 7.681e-5, 0.005e-5);
}

TEST(Stability, RelaxationTime) {
  EXPECT_DOUBLE_EQ(relaxationTime(2.0, 4.0), 0.5);
  EXPECT_TRUE(std::isinf(relaxationTime(1.0, 0.0)));
}

namespace {
Scenario baseScenario() {
  return parseScenario(R"(
name: s
participants:
  particles: { adapter: free-particles }
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 0.01 }
constants: { particle_density: 1750, youngs_modulus: 5.0e6, poisson_ratio: 0.3 }
)",
                       fs::temp_directory_path() / "s.yaml");
}
link::ParticleData grains(double r) {
  link::ParticleData d;
  d.ids = {1, 2};
  d.field(field::radius) = {r, r};
  return d;
}
}  // namespace

// checks.particle_count: 2 grains of r = 1 mm at 1750 kg/m3 are 2 x 4/3 pi 1e-9 x 1750 =
// 1.4661e-5 kg; 3 asked for would weigh 2.1991e-5 kg (-33.3 %).
TEST(Stability, AParticleCountOtherThanTheScenesStopsTheRunWithWhatWasPlaced) {
  Scenario sc = baseScenario();
  EXPECT_FALSE(checkParticleCount(sc, grains(1e-3)));  // not asked for: not checked
  sc = parseScenario(R"(
name: s
participants:
  particles: { adapter: free-particles }
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 0.01 }
constants: { particle_density: 1750 }
checks: { particle_count: 3 }
)",
                     fs::temp_directory_path() / "s.yaml");
  ASSERT_EQ(sc.checks.particle_count, 3u);
  const auto fewer = checkParticleCount(sc, grains(1e-3));
  ASSERT_TRUE(fewer);
  EXPECT_NE(fewer->find("hold 2 particles"), std::string::npos) << *fewer;
  EXPECT_NE(fewer->find("asks for 3 (-33.3 %)"), std::string::npos) << *fewer;
  EXPECT_NE(fewer->find("weigh 1.466e-05 kg where 2.199e-05 kg"), std::string::npos) << *fewer;
  EXPECT_NE(fewer->find("could not place them all"), std::string::npos) << *fewer;
  sc.checks.particle_count = 2;
  EXPECT_FALSE(checkParticleCount(sc, grains(1e-3)));
  sc.checks.particle_count = 1;
  const auto more = checkParticleCount(sc, grains(1e-3));
  ASSERT_TRUE(more);
  EXPECT_NE(more->find("(+100.0 %)"), std::string::npos) << *more;
  EXPECT_NE(more->find("holds more than the scene asks for"), std::string::npos) << *more;
}

TEST(Stability, AParticleCountThatIsNotAWholePositiveNumberIsBlamedOnItsKey) {
  for (const char* bad : {"2.5", "0", "-3", "many"}) {
    try {
      parseScenario(std::string(R"(
name: s
participants:
  particles: { adapter: free-particles }
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 0.01 }
checks: { particle_count: )") +
                        bad + " }\n",
                    fs::temp_directory_path() / "s.yaml");
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("checks.particle_count"), std::string::npos) << e.what();
    }
  }
}

TEST(Stability, StiffContactsAreRefusedWithTheStepThatWouldWork) {
  Scenario sc = baseScenario();  // DEM dt 1e-4 vs t_R 7.7e-5: ratio 1.3
  auto rep = checkBeforeRun(sc, {}, {}, grains(0.75e-3));
  ASSERT_EQ(rep.refusals.size(), 1u);
  // dem_steps >= ceil(1e-4 / (0.2 * 7.681e-5)) = ceil(6.51) = 7
  EXPECT_NE(rep.refusals[0].find("dem_steps >= 7"), std::string::npos) << rep.refusals[0];
  sc.coupling.dem_steps = 10;  // ratio 0.13: fine
  EXPECT_TRUE(checkBeforeRun(sc, {}, {}, grains(0.75e-3)).refusals.empty());
}

// One source of material data: the particle participant's own ratio (what its contacts are
// computed with) wins over the scenario's constants, which are named when they disagree.
TEST(Stability, TheParticleParticipantsOwnRayleighRatioIsTheOneJudged) {
  Scenario sc = baseScenario();
  sc.coupling.dem_steps = 10;  // from the constants: 1e-5 / 7.681e-5 = 0.13, fine
  // The participant reports 1.31 (its script is stiffer): refused with the steps for its t_R
  auto rep = checkBeforeRun(sc, {}, {}, grains(0.75e-3), 1.31);
  ASSERT_EQ(rep.refusals.size(), 1u);
  // t_R = 1e-5 / 1.31 = 7.634e-6 s; dem_steps >= ceil(1e-4 / (0.2 t_R)) = ceil(65.5) = 66
  EXPECT_NE(rep.refusals[0].find("dem_steps >= 66"), std::string::npos) << rep.refusals[0];
  EXPECT_NE(rep.refusals[0].find("own material data"), std::string::npos) << rep.refusals[0];
  bool warned = false;
  for (const auto& l : rep.lines)
    warned = warned || (l.find("warning: constants.youngs_modulus") != std::string::npos &&
                        l.find("0.13") != std::string::npos);
  EXPECT_TRUE(warned) << "the disagreeing constants are named";
  // Agreeing data: no warning, and without constants the reported ratio alone decides
  rep = checkBeforeRun(sc, {}, {}, grains(0.75e-3), 1e-5 / 7.681e-5);
  EXPECT_TRUE(rep.refusals.empty());
  for (const auto& l : rep.lines) EXPECT_EQ(l.find("warning"), std::string::npos) << l;
  sc.constants.material.youngs_modulus = 0;
  EXPECT_EQ(checkBeforeRun(sc, {}, {}, grains(0.75e-3), 1.31).refusals.size(), 1u);
  EXPECT_TRUE(checkBeforeRun(sc, {}, {}, grains(0.75e-3)).refusals.empty())
      << "neither source: no judgement";
}

TEST(Stability, CellsSmallerThanAParcelAreRefused) {
  Scenario sc = baseScenario();
  auto state = grains(1e-3);  // d = 2 mm
  link::ParticleData samples;
  samples.ids = state.ids;
  samples.field(field::cell_size) = {1.5e-3, 1.5e-3};  // 0.75 d
  auto rep = checkFirstStep(sc, state, samples, {});
  ASSERT_EQ(rep.refusals.size(), 1u);
  EXPECT_NE(rep.refusals[0].find(">= 0.004 m"), std::string::npos) << rep.refusals[0];
  samples.field(field::cell_size) = {6e-3, 6e-3};  // 3 d: ok
  rep = checkFirstStep(sc, state, samples, {});
  EXPECT_TRUE(rep.refusals.empty());
  EXPECT_NE(rep.lines.back().find("ok"), std::string::npos);
}

TEST(Stability, RelaxationTimeIsReportedAgainstTheIntervals) {
  Scenario sc = baseScenario();
  auto state = grains(1e-4);
  link::ParticleData forcing;
  forcing.ids = state.ids;
  // m = 1750 * 4/3 pi 1e-12 = 7.330e-9 kg; K = 7.330e-9 / 1e-6 -> tau = 1e-6 s = dt / 100
  const double m = 1750 * 4.0 / 3.0 * M_PI * 1e-12;
  forcing.field(field::drag_coefficient) = {m / 1e-6, m / 1e-5};
  auto rep = checkFirstStep(sc, state, {}, forcing);
  ASSERT_FALSE(rep.lines.empty());
  EXPECT_NE(rep.lines[0].find("coupling interval = 100 tau_p"), std::string::npos) << rep.lines[0];
  EXPECT_NE(rep.lines[0].find("particle 1"), std::string::npos);
}

TEST(Monitor, ParticleLedger) {
  Scenario sc = baseScenario();
  StepMonitor m(sc);
  EXPECT_NO_THROW(m.checkParticleLedger({1, 2, 3}, {1, 3, 4}, {4}, {2}, 5, 0.1));
  try {
    m.checkParticleLedger({1, 2, 3}, {1, 3}, {}, {}, 6, 0.2);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("first vanished id 2"), std::string::npos) << e.what();
  }
}

// The peer path between records: the particles send who came and went, the orchestrator keeps the
// ids (sorted) and refuses changes that do not add up, naming the parcel, its ids left as they
// were.
TEST(Monitor, ParticleChangesOfThePeerPathAddUpOrAreRefused) {
  std::vector<std::int64_t> ids = {1, 2, 3, 5};
  EXPECT_FALSE(applyParticleChanges(ids, {7, 4}, {2}, 5));
  EXPECT_EQ(ids, (std::vector<std::int64_t>{1, 3, 4, 5, 7}));
  EXPECT_FALSE(applyParticleChanges(ids, {}, {}, 5));  // the common step: nothing to do
  EXPECT_EQ(ids, (std::vector<std::int64_t>{1, 3, 4, 5, 7}));
  const std::vector<std::int64_t> before = ids;
  auto refused = [&](std::vector<std::int64_t> in, std::vector<std::int64_t> out,
                     std::uint64_t count, const std::string& says) {
    const auto wrong = applyParticleChanges(ids, std::move(in), std::move(out), count);
    ASSERT_TRUE(wrong) << says;
    EXPECT_NE(wrong->find(says), std::string::npos) << *wrong;
    EXPECT_EQ(ids, before) << *wrong;
  };
  refused({}, {9}, 4, "deleted parcel 9, which it did not hold");
  refused({3}, {}, 6, "inserted parcel 3, which it already held");
  refused({8, 8}, {}, 7, "inserted parcel 8 twice");
  refused({}, {4, 4}, 3, "deleted parcel 4 twice");
  refused({8}, {1}, 6,
          "holds 6 parcels, where the 5 it held with the 1 it inserted and the 1 it "
          "deleted make 5");
}

TEST(Monitor, WholeStateAgainstTheReportedChanges) {
  const std::vector<std::int64_t> known = {1, 3, 4};
  EXPECT_FALSE(compareWithChanges(known, {4, 1, 3}));  // any order
  EXPECT_EQ(compareWithChanges(known, {4, 1}).value_or(""),
            "lacks parcel 3, which it never reported deleted");
  EXPECT_EQ(compareWithChanges(known, {4, 1, 3, 9}).value_or(""),
            "holds parcel 9, which it never reported inserted");
  EXPECT_EQ(compareWithChanges(known, {4, 2, 3, 1}).value_or(""),
            "holds parcel 2, which it never reported inserted");
  EXPECT_EQ(compareWithChanges(known, {}).value_or(""),
            "lacks parcel 1, which it never reported deleted");
}

// The paper's vessel at 1 L/min: the precursor's fraction fell to -4.2e-6 in 37 of 28,136 cells
// (largest 0.011, the nozzle's): warned once, naming the value and the remedy; round-off is not.
TEST(Monitor, PrecursorBelowZeroWarnsOnce) {
  Scenario sc = baseScenario();
  StepMonitor m(sc);
  EXPECT_FALSE(m.checkPrecursorBounds(0.0, 0.011, 1, 1e-4));
  EXPECT_FALSE(m.checkPrecursorBounds(-1e-18, 0.011, 2, 2e-4));  // round-off
  EXPECT_FALSE(m.checkPrecursorBounds(-1e-9, 0.0, 3, 3e-4));     // nothing fed: no scale
  const auto w = m.checkPrecursorBounds(-4.2e-6, 0.011, 4, 4e-4);
  ASSERT_TRUE(w);
  EXPECT_NE(w->find("-4.2e-06"), std::string::npos) << *w;
  EXPECT_NE(w->find("step 4"), std::string::npos) << *w;
  EXPECT_NE(w->find("limited corrected"), std::string::npos) << *w;
  EXPECT_FALSE(m.checkPrecursorBounds(-1e-5, 0.011, 5, 5e-4));  // once
}

TEST(Monitor, CourantWarnsOnceThenStops) {
  Scenario sc = baseScenario();
  StepMonitor m(sc);
  EXPECT_FALSE(m.checkCourant(0.5, 1, 0.0));
  EXPECT_TRUE(m.checkCourant(1.5, 2, 0.0));
  EXPECT_FALSE(m.checkCourant(1.6, 3, 0.0));
  try {
    m.checkCourant(10.0, 4, 0.0);
    FAIL();
  } catch (const std::runtime_error& e) {
    // dt 1e-4 * 0.5 / 10 = 5e-6
    EXPECT_NE(std::string(e.what()).find("5e-06"), std::string::npos) << e.what();
  }
  // With DEM steps to halve: the resume that goes on with half the coupling step
  sc.coupling.dem_steps = 20;
  StepMonitor twenty(sc);
  try {
    twenty.checkCourant(10.0, 4, 0.0);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--set coupling.dt=5e-05 --set coupling.dem_steps=10"),
              std::string::npos)
        << e.what();
  }
}

TEST(Monitor, MassBalanceDriftStops) {
  Scenario sc = baseScenario();
  StepMonitor m(sc);
  m.checkMassBalance(1.0, 0.2, 0.3, 0.5, 1, 0.0);  // baseline (initial content unknown)
  EXPECT_NO_THROW(
      m.checkMassBalance(2.0, 0.6, 0.5, 0.9, 2, 0.0));  // +1 in = +0.4 out +0.2 held +0.4 removed
  EXPECT_THROW(m.checkMassBalance(3.0, 1.0, 0.7, 1.0, 3, 0.0), std::runtime_error);  // 0.2 missing
}

TEST(Stability, RefusedRunStopsBeforeAnyStepWithTheAdvice) {
  const fs::path dir = fs::temp_directory_path() / ("cosim-stiff-" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scenario.yaml") << R"(
name: stiff
participants:
  particles:
    adapter: free-particles
    options: { density: 1750, particles: [ { position: [0, 0, 0], radius: 0.75e-3 } ] }
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 0.01 }
constants: { particle_density: 1750, youngs_modulus: 5.0e9, poisson_ratio: 0.3 }
)";
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  Coupler c(loadScenario(dir), o);
  std::size_t steps = 0;
  c.on_step = [&](double, const link::ParticleData&) { ++steps; };
  auto r = c.run();
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(steps, 0u);
  EXPECT_NE(r.message.find("refused"), std::string::npos) << r.message;
  // t_R scales as E^-1/2: 7.681e-5 / sqrt(1000) = 2.429e-6 s; dem_steps >= ceil(1e-4/4.858e-7) =
  // 206
  EXPECT_NE(r.message.find("dem_steps >= 206"), std::string::npos) << r.message;
}

// The per-step check of what a peer sent: every field finite, no parcel faster than
// checks.max_particle_speed, voidage in (0, 1]; the message names the field, the particle id,
// the value and the step.
TEST(Stability, AParticleStateCheckNamesTheFirstBadValue) {
  link::ParticleData s;
  s.ids = {7, 8, 9, 10, 11};
  s.field(field::position) = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4};
  s.field(field::velocity) = {0,  0, 1, 3, 0, 4, 0, 0,
                              -2, 1, 1, 1, 0, 0, 0};  // 1, 5, 2, 1.73, 0 m/s
  s.field(field::voidage) = {0.4, 0.5, 1.0, 0.9, 0.99};
  EXPECT_FALSE(checkParticleState(s, "particles", 5.0, 3, 0.3));  // 5 m/s is not above 5
  const auto fast = checkParticleState(s, "particles", 4.5, 3, 0.3);
  ASSERT_TRUE(fast);
  EXPECT_NE(fast->find("particle 8 moves at 5 m/s at step 3"), std::string::npos) << *fast;
  EXPECT_NE(fast->find("checks.max_particle_speed = 4.5"), std::string::npos) << *fast;

  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {std::nan(""), inf, -inf}) {
    link::ParticleData b = s;
    b.field(field::position)[13] = bad;  // particle 11, y
    const auto msg = checkParticleState(b, "fluid", 100.0, 4, 0.4);
    ASSERT_TRUE(msg);
    EXPECT_NE(msg->find("fluid: position of particle 11 is"), std::string::npos) << *msg;
    EXPECT_NE(msg->find("at step 4"), std::string::npos) << *msg;
  }
  link::ParticleData e = s;
  e.field(field::voidage)[2] = 1.0 + 1e-6;
  const auto out = checkParticleState(e, "fluid", 100.0, 5, 0.5);
  ASSERT_TRUE(out);
  EXPECT_NE(out->find("voidage 1.000001 at particle 9 (step 5) is outside (0, 1]"),
            std::string::npos)
      << *out;
  e.field(field::voidage)[2] = 1.0 + 1e-12;  // round-off above 1 is accepted
  EXPECT_FALSE(checkParticleState(e, "fluid", 100.0, 5, 0.5));
}

// A checkpoint interval below the coupling step (a typo of 1e-9 for 1e-1) checkpoints after
// every step: said before the run, with the count and a usable interval; no warning otherwise.
TEST(Stability, ACheckpointIntervalBelowTheCouplingStepIsNamedBeforeTheRun) {
  Scenario sc = baseScenario();
  sc.coupling.dem_steps = 10;
  sc.coupling.start_time = 0.0;
  sc.coupling.end_time = 1.0;  // 10,000 steps of 1e-4 s
  auto said = [&] {
    std::string all;
    for (const auto& l : checkBeforeRun(sc, {}, {}, grains(0.75e-3)).lines) all += l + "\n";
    return all;
  };
  sc.checkpoint.interval = 1e-9;
  const std::string text = said();
  EXPECT_NE(text.find("warning: checkpoint.interval 1e-09 s is shorter than the coupling "
                      "interval 0.0001 s"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("(10000 in this run)"), std::string::npos) << text;
  EXPECT_NE(text.find("checkpoint.interval: 0.1)"), std::string::npos) << text;
  sc.checkpoint.interval = 0.1;
  EXPECT_EQ(said().find("checkpoint.interval"), std::string::npos) << said();
  sc.checkpoint.interval = 0.0;
  EXPECT_EQ(said().find("checkpoint.interval"), std::string::npos) << said();
}

// particles.h5's growth, by hand: 1,000 particles with position (3) and radius (1) recorded, the
// ids beside them: 5,000 doubles = 40,000 bytes plus 4,096 of group and attributes a snapshot.
// 1 s at output.interval 0.01 s: 101 snapshots (the one at the start too) = 4,453,696 bytes;
// from t = 0.5 s (a resumed run), 51 = 2,248,896. An interval below the coupling step records
// every step (10,001 snapshots).
TEST(Stability, AnOutputLargerThanTheFreeDiskIsNamedBeforeTheRunWithAnIntervalThatFits) {
  Scenario sc = baseScenario();
  sc.coupling.start_time = 0.0;
  sc.coupling.end_time = 1.0;
  sc.output.interval = 0.01;
  Plan plan;
  plan.particles_send = {field::position, field::radius, "not_reported"};
  link::ParticleData s;
  for (int i = 1; i <= 1000; ++i) s.ids.push_back(i);
  s.field(field::position).assign(3000, 0.0);
  s.field(field::radius).assign(1000, 1e-3);
  s.field(field::velocity).assign(3000, 0.0);  // reported, not recorded: not counted
  EXPECT_DOUBLE_EQ(particleOutputBytes(sc, plan, s, 0.0), 101 * 44096.0);
  EXPECT_DOUBLE_EQ(particleOutputBytes(sc, plan, s, 0.5), 51 * 44096.0);
  EXPECT_FALSE(checkDiskSpace(sc, plan, s, 0.0, 1e9));                  // 4.5 MB of 1 GB
  EXPECT_FALSE(checkDiskSpace(sc, plan, s, 0.0, 101 * 44096.0 / 0.8));  // just fits
  const auto w = checkDiskSpace(sc, plan, s, 0.0, 1e6);
  ASSERT_TRUE(w);
  EXPECT_NE(w->find("warning: particles.h5 will grow by about 0.00445 GB over the run (101 "
                    "snapshots of 1000 particles, output.interval 0.01 s), but only 0.001 GB"),
            std::string::npos)
      << *w;
  // half of 1 MB is 1 / 8.91 of that: one snapshot every 8.91 x 0.01 s
  EXPECT_NE(w->find("output.interval: 0.0891 would take half of the free space"), std::string::npos)
      << *w;
  sc.output.interval = 0.0;
  EXPECT_DOUBLE_EQ(particleOutputBytes(sc, plan, s, 0.0), 10001 * 44096.0);
}

// The disk's filling during a run, by hand: 1000 MB free at t = 0, 900 MB at t = 10 s is 10 MB
// per simulated second, so the 900 MB left last 90 s more: full at t = 100 s. A run to 200 s is
// warned; one to 100 s (full exactly at its end) or 50 s is not, nor a disk that did not fill.
TEST(Stability, ADiskFillingBeforeTheRunsEndIsNamedWithItsRateAndTime) {
  int asked = 0;
  const auto largest = [&] {
    ++asked;
    return std::string("fluid.log 80.0 MB");
  };
  const auto w = checkDiskFilling(0, 1000e6, 10, 900e6, 200, largest);
  ASSERT_TRUE(w);
  for (const char* f :
       {"filling by 10.0 MB per simulated second since t = 0 s",
        "it is full at t = 100 s, before the run's end at 200 s (900.0 MB free now)",
        "The largest parts of the run folder: fluid.log 80.0 MB", "solver_log_every"})
    EXPECT_NE(w->find(f), std::string::npos) << f << " in: " << *w;
  EXPECT_FALSE(checkDiskFilling(0, 1000e6, 10, 900e6, 100, largest));
  EXPECT_FALSE(checkDiskFilling(0, 1000e6, 10, 900e6, 50, largest));
  EXPECT_FALSE(checkDiskFilling(0, 900e6, 10, 1000e6, 200, largest));   // space was freed
  EXPECT_FALSE(checkDiskFilling(10, 1000e6, 10, 900e6, 200, largest));  // no time has passed
  EXPECT_EQ(asked, 1) << "the folder's parts are looked up only for a warning";
}

// The largest entries of a folder, folders with their contents' size, largest first.
TEST(Stability, TheLargestPartsOfARunFolderAreNamedWithTheirSizes) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cosim-largest-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "fluid" / "0.1");
  std::ofstream(dir / "fluid.log") << std::string(3'000'000, 'x');
  std::ofstream(dir / "fluid" / "0.1" / "U") << std::string(2'000'000, 'u');
  std::ofstream(dir / "summary.json") << std::string(1'000, 's');
  EXPECT_EQ(largestEntries(dir, 2), "fluid.log 3.0 MB, fluid/ 2.0 MB");
  EXPECT_EQ(largestEntries(dir, 5), "fluid.log 3.0 MB, fluid/ 2.0 MB, summary.json 1.0 kB");
  std::filesystem::remove_all(dir);
}
