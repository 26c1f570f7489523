#include "cosim/analysis/report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/summary.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "synthetic.h"

namespace fs = std::filesystem;
using namespace cosim::analysis;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A synthetic run folder as `cosim run` writes it: particles.h5 (+ .xmf) every 0.5 s for 20 s,
// and a time series with one row per 0.1 s coupling step in the orchestrator's convention
// (cumulative amounts, the coating removed in a step credited one step later, a final row after
// the final credit), whose precursor balance closes exactly by construction.
fs::path makeRun(const std::string& name, double uncoated_share, std::uint64_t seed) {
  const fs::path dir =
      fs::temp_directory_path() / ("cosim_report_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::mt19937_64 rng(seed);
  const std::size_t n = 1500;
  const double a1 = 4e-9, a2 = 1e-9, dt = 0.5;
  const auto masses = test::trackedCoating(rng, n, a1, a2, dt, 40, uncoated_share);
  ParticleRecorder rec(dir, {cosim::field::position, cosim::field::coating_mass},
                       {"synthetic", 1.0});
  TimeSeriesRecorder ts(
      dir / kTimeSeriesFile,
      {column::particle_count, column::wall_seconds, column::precursor_in, column::precursor_out,
       column::precursor_held, column::precursor_removed, column::coated_mass});
  {
    // The orchestrator records the initial state (uncoated) before the first step.
    cosim::link::ParticleData p0;
    p0.ids.resize(n);
    for (std::size_t i = 0; i < n; ++i) p0.ids[i] = static_cast<std::int64_t>(i + 1);
    p0.field(cosim::field::position);
    p0.field(cosim::field::coating_mass);
    rec.write(0.0, p0);
  }
  double in = 0, out = 0, held = 0, removed = 0, credited = 0, pending = 0, wall = 0,
         coatedPrev = 0;
  for (std::size_t s = 0; s < masses.size(); ++s) {
    const double t = dt * static_cast<double>(s + 1);
    cosim::link::ParticleData p;
    p.ids.resize(n);
    for (std::size_t i = 0; i < n; ++i) p.ids[i] = static_cast<std::int64_t>(i + 1);
    auto& pos = p.field(cosim::field::position);
    for (std::size_t i = 0; i < 3 * n; ++i) pos[i] = 1e-3 * static_cast<double>(i % 97);
    p.field(cosim::field::coating_mass) = masses[s];
    rec.write(t, p);
    double coated = 0;
    for (double m : masses[s]) coated += m;
    const double gained = coated - coatedPrev;
    for (int k = 1; k <= 5; ++k) {
      const double step = t - dt + 0.1 * k;
      const double newHeld = 1e-7 * (1.0 - std::exp(-step));
      const double stepIn = 2e-6, stepRemoved = gained / 5.0;
      credited += pending;  // last step's removal credited now
      pending = stepRemoved;
      in += stepIn;
      out += stepIn - (newHeld - held) - stepRemoved;
      removed += stepRemoved;
      held = newHeld;
      wall += 0.02;
      ts.write(step, {static_cast<double>(n), wall, in, out, held, removed, credited});
    }
    coatedPrev = coated;
  }
  credited += pending;
  ts.write(dt * 40, {static_cast<double>(n), wall, in, out, held, removed, credited});
  return dir;
}

// Removes the synthetic runs of a test that passed (a failed one keeps them to look at).
struct CleanUp {
  fs::path dir;
  ~CleanUp() {
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
  }
};

bool matplotlibAvailable() {
  std::string why;
  return findPython(why).has_value() && findPlotScript().has_value();
}
}  // namespace

TEST(Report, SingleWellMixedRunEndToEnd) {
  const fs::path run = makeRun("well-mixed", 0.0, 17);
  CleanUp cleanup{run.parent_path()};
  ReportOptions o;
  o.runs = {run};
  o.fit_end = 10.0;  // the last 10 s check the prediction
  std::ostringstream log;
  o.log = &log;
  ASSERT_EQ(runReport(o), 0) << log.str();
  const fs::path out = run / "report";
  for (const char* f : {"report.json", "report.html", "statistics.csv", "histograms.csv", "fit.csv",
                        "fit_residuals.csv", "cv_prediction.csv", "distributions.csv",
                        "prediction_check.csv", "window_study.csv", "mass_balance.csv"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  const std::string json = slurp(out / "report.json");
  EXPECT_NE(json.find("\"well_mixed\": true"), std::string::npos);
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("Well mixed: extrapolation allowed."), std::string::npos);
  EXPECT_NE(html.find("Mass balance (paper Table 3)"), std::string::npos);
  EXPECT_NE(html.find("Error against run time"), std::string::npos);
  EXPECT_NE(html.find("Prediction checked against the 20 simulated snapshots"), std::string::npos);
  EXPECT_NE(log.str().find("mass balance error"), std::string::npos) << log.str();

  const auto a = analyseRun(run, o);
  ASSERT_TRUE(a.mass_balance.has_value());
  // Closed by construction: only round-off remains.
  EXPECT_LT(std::abs(a.mass_balance->error_percent), 1e-8);
  EXPECT_NEAR(a.fit.a1, 4e-9, 0.02 * 4e-9);
  // The synthetic bed follows the same parcels: the bootstrap error of a2 is what the report
  // shows, and it is several times the regression error.
  ASSERT_TRUE(a.bootstrap.ok) << a.bootstrap.problem;
  EXPECT_EQ(a.bootstrap.parcels, 1500u);
  EXPECT_EQ(a.bootstrap.snapshots, 20u);  // the fitted snapshots 0.5 .. 10 s
  EXPECT_DOUBLE_EQ(a.a2Error(), a.bootstrap.a2_se);
  EXPECT_GT(a.bootstrap.a2_se, 2 * a.fit.a2_se);
  EXPECT_LT(std::abs(a.fit.a2 - 1e-9), 4 * a.a2Error());
  EXPECT_NEAR(a.mass_balance->pending, 0.0, 1e-12 * a.mass_balance->removed);
  // Read on the particles (particles.h5 holds the initial and the final state).
  EXPECT_NE(a.mass_balance->obtained_source.find("particles.h5"), std::string::npos);
  EXPECT_EQ(a.steps, 201u);
  EXPECT_NEAR(a.wall_seconds, 200 * 0.02, 1e-9);

  if (!matplotlibAvailable())
    GTEST_SKIP() << "python3 with matplotlib not available: PNGs not checked";
  for (const char* png :
       {"histograms.png", "statistics_time.png", "cv_mean.png", "fit.png", "cv_prediction.png",
        "distributions.png", "window_study.png", "mass_balance.png"}) {
    ASSERT_TRUE(fs::exists(out / png)) << png << "\n" << slurp(out / "plot_report.log");
    EXPECT_GT(fs::file_size(out / png), 1000u) << png;
    EXPECT_NE(html.find(std::string("src=\"") + png + "\""), std::string::npos) << png;
  }
}

TEST(Report, SweepComparesRunsAndRefusesThePoorlyMixedOne) {
  const fs::path good = makeRun("flow-100", 0.0, 23);
  const fs::path poor = makeRun("flow-1", 0.2, 29);
  const fs::path out = good.parent_path() / "sweep-report";
  CleanUp cleanup{good.parent_path()};
  for (const auto& [run, flow] : {std::pair{good, 100.0}, std::pair{poor, 1.0}}) {
    Summary s;
    s.status = "completed";
    s.parameters = {{"flow_lpm", flow}, {"cg", 5.0}};  // cg: same in both runs, not a column
    writeSummary(run / kSummaryFile, s);
  }
  ReportOptions o;
  o.runs = {poor, good};
  o.output = out;
  std::ostringstream log;
  o.log = &log;
  ASSERT_EQ(runReport(o), 0) << log.str();
  EXPECT_TRUE(fs::exists(out / "flow-1" / "report.html"));
  EXPECT_TRUE(fs::exists(out / "flow-100" / "report.html"));
  const std::string html = slurp(out / "comparison.html");
  const auto poorRow = html.find(">flow-1<");
  const auto goodRow = html.find(">flow-100<");
  ASSERT_NE(poorRow, std::string::npos);
  ASSERT_NE(goodRow, std::string::npos);
  EXPECT_NE(html.find("poorly mixed", poorRow), std::string::npos);
  EXPECT_NE(html.find("never coated", poorRow), std::string::npos);
  EXPECT_NE(html.find("well mixed", goodRow), std::string::npos);
  EXPECT_NE(slurp(out / "flow-1" / "report.html").find("Poorly mixed: extrapolation refused."),
            std::string::npos);
  // The parameter that differs between the runs is a column; the one that does not is not.
  EXPECT_NE(html.find("<th>flow_lpm</th>"), std::string::npos);
  EXPECT_EQ(html.find("<th>cg</th>"), std::string::npos);
  EXPECT_NE(slurp(out / "comparison.json").find("\"legend\": \"flow-1 flow_lpm=1\""),
            std::string::npos);
  const std::string csv = slurp(out / "comparison.csv");
  EXPECT_NE(csv.find("\"flow-1\""), std::string::npos);
  if (!matplotlibAvailable())
    GTEST_SKIP() << "python3 with matplotlib not available: PNGs not checked";
  for (const char* png :
       {"compare_cv_mean.png", "compare_statistics_time.png", "compare_histograms.png"}) {
    EXPECT_TRUE(fs::exists(out / png)) << png << "\n" << slurp(out / "plot_report.log");
  }
  // A poorly mixed run gets the full set of figures, but no extrapolation in them.
  for (const char* png :
       {"histograms.png", "statistics_time.png", "cv_mean.png", "fit.png", "cv_prediction.png",
        "distributions.png", "window_study.png", "mass_balance.png"}) {
    EXPECT_TRUE(fs::exists(out / "flow-1" / png)) << png;
  }
  EXPECT_NE(slurp(out / "flow-1" / "report.html").find("no prediction, the run is poorly mixed"),
            std::string::npos);
}

TEST(Report, WithoutMatplotlibTheNumbersAndHtmlStillComeOutAndSayWhatToInstall) {
  const fs::path run = makeRun("no-python", 0.0, 31);
  CleanUp cleanup{run.parent_path()};
  ::setenv("COSIM_PYTHON", "/nonexistent/python3", 1);
  ReportOptions o;
  o.runs = {run};
  std::ostringstream log;
  o.log = &log;
  const int rc = runReport(o);
  ::unsetenv("COSIM_PYTHON");
  ASSERT_EQ(rc, 0) << log.str();
  const fs::path out = run / "report";
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "statistics.csv"));
  EXPECT_TRUE(fs::exists(out / "mass_balance.csv"));
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".png") << e.path();
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("Plots missing"), std::string::npos);
  EXPECT_NE(html.find("apt-get install python3-matplotlib"), std::string::npos);
  EXPECT_NE(html.find("<td class=l>precursor in</td>"), std::string::npos);
  EXPECT_NE(log.str().find("but no plots"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("/nonexistent/python3"), std::string::npos) << log.str();
}

TEST(Report, AFailedRunIsReportedAsFarAsItGot) {
  const fs::path run = makeRun("failed", 0.0, 37);
  CleanUp cleanup{run.parent_path()};
  Summary s;
  s.status = "failed";
  s.message = "participant 'fluid': timeout";
  writeSummary(run / kSummaryFile, s);
  ReportOptions o;
  o.runs = {run};
  o.plots = false;
  std::ostringstream log;
  o.log = &log;
  ASSERT_EQ(runReport(o), 0) << log.str();
  const std::string html = slurp(run / "report" / "report.html");
  EXPECT_NE(html.find("The run did not complete (summary.json status: failed)"), std::string::npos);
}

TEST(Report, BadOptionsAreClearErrors) {
  ReportOptions o;
  o.runs = {"/nonexistent/run"};
  o.predict_times = {300, -5};
  testing::internal::CaptureStderr();
  EXPECT_EQ(runReport(o), 1);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("--predict = -5"), std::string::npos) << err;
  o.predict_times = {300};
  o.fit_start = 10;
  o.fit_end = 5;
  testing::internal::CaptureStderr();
  EXPECT_EQ(runReport(o), 1);
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("the window is empty"), std::string::npos) << err;
}

TEST(Report, MassBalanceCheckForCi) {
  const fs::path run = makeRun("check", 0.0, 41);
  CleanUp cleanup{run.parent_path()};
  ReportOptions o;
  o.runs = {run};
  o.plots = false;
  o.mass_balance_limit_percent = 0.01;
  std::ostringstream log;
  o.log = &log;
  EXPECT_EQ(runReport(o), 0) << log.str();
  // Break the balance: the particles lose 1 % of their coating at the end.
  {
    cosim::link::ParticleData p;
    double time = 0;
    {
      ParticleFile f(run / kParticlesFile);  // closed before the recorder opens the file
      const std::size_t last = f.snapshots().size() - 1;
      time = f.snapshots()[last].time;
      p.ids = f.ids(last);
      p.field(cosim::field::position) = f.read(last, cosim::field::position);
      auto m = f.read(last, cosim::field::coating_mass);
      for (auto& x : m) x *= 0.99;
      p.field(cosim::field::coating_mass) = m;
    }
    ParticleRecorder rec(run, {cosim::field::position, cosim::field::coating_mass},
                         {"synthetic", 1.0}, ParticleRecorder::Mode::append);
    rec.write(time, p);  // replaces the last snapshot
  }
  testing::internal::CaptureStderr();
  EXPECT_EQ(runReport(o), 3);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("exceeds the limit 0.01 %"), std::string::npos) << err;
}

TEST(Report, MissingRunIsAClearError) {
  ReportOptions o;
  o.runs = {"/nonexistent/run"};
  std::ostringstream log;
  o.log = &log;
  testing::internal::CaptureStderr();
  EXPECT_EQ(runReport(o), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("/nonexistent/run does not exist"), std::string::npos) << err;
}
