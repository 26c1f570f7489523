// The reduced plasma coating bed with the real solvers (OpenFOAM + LIGGGHTS through the
// orchestrator): the precursor mass balance closes to better than 0.01 %, every gram removed
// from the gas arrives on the particles, and the analytics and report are produced.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "coupler.h"
#include "cosim/analysis/report.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(PlasmaCoatingCi, MassBalanceClosesAndReportIsProduced) {
  const fs::path out = fs::temp_directory_path() / ("cosim-plasma-ci-" + std::to_string(getpid()));
  fs::remove_all(out);
  Scenario sc = loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml");
  RunOptions o;
  o.quiet = true;
  o.output = out;
  Coupler c(std::move(sc), o);
  RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;

  const double in = r.totals.at("precursor_in_kg");
  const double outflow = r.totals.at("precursor_out_kg");
  const double held = r.totals.at("precursor_held_kg");
  const double removed = r.totals.at("precursor_removed_kg");
  const double credited = r.totals.at("coating_credited_kg");
  const double on_particles = r.totals.at("coating_on_particles_kg");
  ASSERT_GT(in, 0.0);
  // The gas balance (paper Table 3): expected coating = in - out - accumulation.
  const double expected = in - outflow - held;
  EXPECT_LT(std::fabs(expected - removed), 1e-4 * in)
      << "in " << in << " out " << outflow << " held " << held << " removed " << removed;
  // What left the gas is what the particles received.
  EXPECT_NEAR(credited, removed, 1e-12 * std::max(removed, 1e-30));
  EXPECT_NEAR(on_particles, credited, 1e-9 * std::max(credited, 1e-30));
  EXPECT_GT(removed, 0.0) << "no coating in the CI run: the zone or the feed is wrong";

  // Analytics and report.
  cosim::analysis::ReportOptions ro;
  ro.runs = {r.folder};
  ro.output = out / "report";
  ro.plots = true;
  EXPECT_EQ(cosim::analysis::runReport(ro), 0);
  EXPECT_TRUE(fs::exists(out / "report" / "report.html"));
  EXPECT_TRUE(fs::exists(out / "report" / "report.json"));
}
