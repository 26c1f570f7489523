// cosim study: Pareto front, --vary parsing, and a real study on the analytic scene.
#include "study.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cosim/analysis/report.h"
#include "observables.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(Study, ParetoFrontByHand) {
  // (cost, error): A(1, 0.5) B(2, 0.1) C(3, 0.2) D(4, 0.01) E(2, 0.1)
  // C is dominated by B; B and E tie (neither strictly better): both stay.
  const std::vector<double> cost{1, 2, 3, 4, 2};
  const std::vector<double> err{0.5, 0.1, 0.2, 0.01, 0.1};
  const auto f = paretoFront(cost, err);
  EXPECT_EQ(f, (std::vector<bool>{true, true, false, true, true}));
}

TEST(Study, ParseVary) {
  auto [k, v] = parseVary("coupling.dem_steps=5,10,20");
  EXPECT_EQ(k, "coupling.dem_steps");
  EXPECT_EQ(v, (std::vector<std::string>{"5", "10", "20"}));
  EXPECT_THROW(parseVary("coupling.dt"), std::runtime_error);
  EXPECT_THROW(parseVary("coupling.dt=1,,2"), std::runtime_error);
}

TEST(Observables, QuantitiesAgainstHandValues) {
  cosim::link::ParticleData s;
  s.ids = {1, 2, 3, 4};
  s.field("velocity") = {0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 6};
  s.field("coating_mass") = {1, 2, 3, 6};
  std::vector<double> t{0.1, 0.2, 0.3, 0.4};
  std::map<std::string, std::vector<double>> series{{"pressure_drop", {10, 20, 30, 50}}};
  std::map<std::string, double> totals{{"precursor_in_kg", 2.5}};
  EXPECT_DOUBLE_EQ(evaluateQuantity("particles.velocity.z.mean", s, t, series, totals, -1), 3.0);
  EXPECT_DOUBLE_EQ(evaluateQuantity("particles.velocity.z.max", s, t, series, totals, -1), 6.0);
  // population std of {1,2,3,6}: mean 3, variance (4+1+0+9)/4 = 3.5
  EXPECT_DOUBLE_EQ(evaluateQuantity("particles.coating_mass.std", s, t, series, totals, -1),
                   std::sqrt(3.5));
  EXPECT_DOUBLE_EQ(evaluateQuantity("particles.coating_mass.cv", s, t, series, totals, -1),
                   std::sqrt(3.5) / 3.0);
  EXPECT_DOUBLE_EQ(evaluateQuantity("series.pressure_drop.mean", s, t, series, totals, 0.25), 40.0);
  EXPECT_DOUBLE_EQ(evaluateQuantity("series.pressure_drop.final", s, t, series, totals, -1), 50.0);
  EXPECT_DOUBLE_EQ(evaluateQuantity("totals.precursor_in_kg", s, t, series, totals, -1), 2.5);
  EXPECT_THROW(evaluateQuantity("particles.velocity.mean", s, t, series, totals, -1),
               std::runtime_error);
  EXPECT_THROW(evaluateQuantity("series.nothing.mean", s, t, series, totals, -1),
               std::runtime_error);
  // No values: the reason says which of the two it was
  const auto whyUndefined = [&](const std::string& q, const cosim::link::ParticleData& state,
                                double after) -> std::string {
    try {
      evaluateQuantity(q, state, t, series, totals, after);
    } catch (const UndefinedQuantity& e) {
      return e.what();
    }
    return "(a value)";
  };
  cosim::link::ParticleData none;
  none.field("coating_mass") = {};
  EXPECT_NE(whyUndefined("particles.coating_mass.mean", none, -1)
                .find("no particle was left in the domain at the end of the run"),
            std::string::npos);
  EXPECT_NE(whyUndefined("series.pressure_drop.mean", s, 0.5)
                .find("no row of timeseries.csv at t >= 0.5 s has a value of pressure_drop (4 "
                      "rows, the last at t = 0.4 s)"),
            std::string::npos)
      << whyUndefined("series.pressure_drop.mean", s, 0.5);
  EXPECT_NEAR(*relativeError(1.01, 1.0), 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(*relativeError(0.5, 0.0), 0.5);
}

// Two coupling intervals of the analytic settling sphere, into a fresh folder, quiet, no plots.
StudyOptions settlingSphereStudy(const std::string& tag) {
  StudyOptions o;
  o.output = fs::temp_directory_path() / (tag + std::to_string(getpid()));
  fs::remove_all(o.output);
  o.scenario = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere";
  o.vary = {parseVary("coupling.dt=1e-4,2e-4")};
  o.quiet = true;
  o.plots = false;
  return o;
}

TEST(Study, RunsVariantsAndWritesTables) {
  StudyOptions o = settlingSphereStudy("cosim-study-");
  const fs::path out = o.output;
  ASSERT_EQ(runStudy(o), 0);
  ASSERT_TRUE(fs::exists(out / "study.csv"));
  ASSERT_TRUE(fs::exists(out / "study.md"));
  std::ifstream csv(out / "study.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_NE(header.find("v_terminal_error"), std::string::npos);
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    // The free-particle adapter integrates exactly: the error is the residual exp(-T/tau) only,
    // T = 5 ms, tau = 0.347 ms -> 5.6e-7, whatever the coupling interval.
    std::stringstream ss(row);
    std::vector<std::string> cells;
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    const double err = std::stod(cells[6]);
    EXPECT_NEAR(err, std::exp(-5e-3 / (2500 * 50e-6 * 50e-6 / 18e-3)), 1e-8);
  }
  EXPECT_EQ(rows, 2);
  // study.json reads back through the same struct it was written from (scripts/plot_study.py
  // reads the same keys).
  const auto study = cosim::analysis::readJsonFile(out / "study.json").get<StudyRecord>();
  EXPECT_EQ(study.vary, (std::vector<std::string>{"coupling.dt"}));
  ASSERT_EQ(study.references.size(), 1u);
  EXPECT_EQ(study.references[0], (std::pair<std::string, std::string>{"v_terminal", "analytic"}));
  ASSERT_EQ(study.variants.size(), 2u);
  for (const auto& v : study.variants) {
    EXPECT_TRUE(v.ok) << v.message;
    EXPECT_GT(v.wall_s, 0.0);
    ASSERT_EQ(v.observables.size(), 1u);
    EXPECT_EQ(v.observables[0].name, "v_terminal");
    ASSERT_TRUE(v.observables[0].error);
    EXPECT_NEAR(*v.observables[0].error, std::exp(-5e-3 / (2500 * 50e-6 * 50e-6 / 18e-3)), 1e-8);
  }
  EXPECT_EQ(study.variants[0].label, "coupling.dt=1e-4");
  EXPECT_EQ(cosim::analysis::Json(study).dump(),
            cosim::analysis::readJsonFile(out / "study.json").dump());
}

TEST(Study, CompletedVariantsAreReadBackNotRunAgain) {
  StudyOptions o = settlingSphereStudy("cosim-study-reuse-");
  const fs::path out = o.output;
  ASSERT_EQ(runStudy(o), 0);
  auto read = [&](const fs::path& f) {
    std::ifstream is(f);
    std::stringstream ss;
    ss << is.rdbuf();
    return ss.str();
  };
  const std::string first = read(out / "study.csv");
  const auto stamp = fs::last_write_time(out / "variant-00" / "summary.json");
  const auto stamp1 = fs::last_write_time(out / "variant-01" / "summary.json");
  // Same study again: nothing re-run, same table (the wall times come from the summaries).
  ASSERT_EQ(runStudy(o), 0);
  EXPECT_EQ(fs::last_write_time(out / "variant-00" / "summary.json"), stamp);
  EXPECT_EQ(read(out / "study.csv"), first);
  // Another reference variant: still nothing re-run.
  o.finest = 0;
  ASSERT_EQ(runStudy(o), 0);
  EXPECT_EQ(fs::last_write_time(out / "variant-01" / "summary.json"), stamp1);
  // A changed scene (another end time) is run again; the earlier run is kept, not written over.
  const std::string first_summary = read(out / "variant-00" / "summary.json");
  o.sets = {"coupling.end_time=4e-3"};
  ASSERT_EQ(runStudy(o), 0);
  EXPECT_NE(fs::last_write_time(out / "variant-00" / "summary.json"), stamp);
  EXPECT_EQ(read(out / "variant-00.previous-1" / "summary.json"), first_summary);
  EXPECT_TRUE(fs::exists(out / "variant-01.previous-1" / "particles.h5"));
  // --rerun runs everything again.
  const auto stamp2 = fs::last_write_time(out / "variant-00" / "summary.json");
  o.rerun = true;
  ASSERT_EQ(runStudy(o), 0);
  EXPECT_NE(fs::last_write_time(out / "variant-00" / "summary.json"), stamp2);
}

// Issue 15: a scenario name holding shell syntax reached a shell when the plot was drawn
// (`system("... '<folder>'")` with the name in the folder): `$(touch X)` created X. Programs
// are now started from argument vectors, so the name is only ever a file name.
TEST(Study, ShellSyntaxInTheStudyFolderIsNeverRun) {
  // A scenario name cannot carry shell syntax any more (names are refused unless safe); the
  // study folder given on the command line can, and it reaches the plot script.
  std::string why;
  if (!cosim::analysis::findPython(why)) GTEST_SKIP() << "the plot is what ran a shell: " << why;
  const fs::path here = fs::current_path();
  const fs::path sandbox =
      fs::temp_directory_path() / ("cosim-study-shell-" + std::to_string(getpid()));
  fs::remove_all(sandbox);
  fs::create_directories(sandbox);
  fs::current_path(sandbox);
  StudyOptions o = settlingSphereStudy("unused-");
  const fs::path folder =
      sandbox / "x'$(touch INJECTED)'\"$(touch INJECTED2)\"`touch INJECTED3`-study";
  o.output = folder;
  o.plots = true;
  const int rc = runStudy(o);
  fs::current_path(here);
  EXPECT_EQ(rc, 0);
  for (const char* f : {"INJECTED", "INJECTED2", "INJECTED3"}) {
    EXPECT_FALSE(fs::exists(sandbox / f)) << f << ": the folder name was run by a shell";
  }
  EXPECT_TRUE(fs::exists(folder / "study.json"));
  EXPECT_TRUE(fs::exists(folder / "error_vs_runtime.png")) << "the plot script got the folder "
                                                              "name verbatim";
  fs::remove_all(sandbox);
}

// A study reads every variant's scene before the first runs: a bad last value is refused at once,
// naming the variant, and no run (nor the study folder) is made.
TEST(Study, AVariantOutsideTheSceneIsRefusedBeforeAnyRuns) {
  StudyOptions o = settlingSphereStudy("cosim-study-refused-");
  o.sets = {"d={value: 5.0e-5, min: 1.0e-6, max: 1.0e-3, doc: \"particle diameter [m]\"}"};
  o.vary = {parseVary("d=5e-5,2e-3")};
  try {
    runStudy(o);
    ADD_FAILURE() << "the study ran with d = 2e-3 outside [1e-6, 1e-3]";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("study variant 2 of 2 (d=2e-3): command line --set d=2e-3: parameters.d: "
                        "0.002 is outside [1e-06, 0.001]",
                        0),
              0u)
        << msg;
  }
  EXPECT_FALSE(fs::exists(o.output));
  o.sets.clear();
  o.vary = {parseVary("coupling.dt=1e-4,-1")};
  EXPECT_THROW(runStudy(o), ScenarioError);
  EXPECT_FALSE(fs::exists(o.output));
}

// A study's table files may replace only an earlier study's: pointed at a folder holding someone's
// study.md, it is refused before the first variant runs, and the file stays as it was.
TEST(Study, AFolderWithSomeoneElsesStudyFilesIsRefusedBeforeAnyRuns) {
  StudyOptions o = settlingSphereStudy("cosim-study-foreign-");
  fs::create_directories(o.output);
  std::ofstream(o.output / "study.md") << "# my own notes\n";
  try {
    runStudy(o);
    ADD_FAILURE() << "the study ran into a folder with someone's study.md";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("study.md already exists"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(o.output / "variant-00"));
  std::ifstream in(o.output / "study.md");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# my own notes");
  fs::remove_all(o.output);
}
