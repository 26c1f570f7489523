// The reduced plasma coating bed with the real solvers (OpenFOAM + LIGGGHTS through the
// orchestrator): the precursor mass balance closes to better than 0.01 %, every gram removed
// from the gas arrives on the particles, and the analytics and report are produced.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <filesystem>

#include "cosim/link/fields.h"
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

  // A miniature of the real bed, not grains resting in the bottom cell: 1500 parcels of 1.5 mm
  // over the 20 x 20 mm plate less the 4 x 4 mm nozzle at a packed voidage of about 0.42 make a
  // bed 1500 * pi/6 * (1.5e-3)^3 / ((0.02^2 - 0.004^2) * 0.58) = 11.9 mm deep, three 4 mm cells.
  // Fluidized at 0.21 m/s (about 3 u_mf) with the jet through its centre, a real share of the
  // parcels passes the afterglow within 0.05 s.
  const auto& x = r.final_state.get(cosim::field::position);
  const auto& m = r.final_state.get(cosim::field::coating_mass);
  const std::size_t n = r.final_state.size();
  ASSERT_EQ(n, 1500u);
  std::vector<double> z;
  std::size_t coated = 0;
  for (std::size_t i = 0; i < n; ++i) {
    z.push_back(x[3 * i + 2]);
    coated += m[i] > 0.0 ? 1 : 0;
  }
  std::sort(z.begin(), z.end());
  const double z90 = z[n * 9 / 10];
  std::printf("CI bed: 90th percentile of parcel height %.2f mm, coated %.1f %% of the parcels\n",
              1e3 * z90, 100.0 * double(coated) / double(n));
  EXPECT_GT(z90, 0.008) << "the bed must span more than two cells";
  EXPECT_GT(double(coated), 0.08 * double(n)) << "too few parcels pass the coating zone";
  EXPECT_LT(coated, n) << "every parcel coated in 0.05 s: the zone covers the whole bed";

  // Analytics and report.
  cosim::analysis::ReportOptions ro;
  ro.runs = {r.folder};
  ro.output = out / "report";
  ro.plots = true;
  EXPECT_EQ(cosim::analysis::runReport(ro), 0);
  EXPECT_TRUE(fs::exists(out / "report" / "report.html"));
  EXPECT_TRUE(fs::exists(out / "report" / "report.json"));
}
