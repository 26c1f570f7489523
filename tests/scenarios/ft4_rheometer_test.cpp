// The FT4 rheometer scene with the real solvers at its tiny size (scenarios/ft4-rheometer/
// tiny.yaml, OpenFOAM + LIGGGHTS through the orchestrator): the blade rows of
// particles/ft4_blade.csv follow the prescribed motion, carry no force or torque while the
// blade waits above the bed, resist it once it is in the powder, and `cosim ft4 energy` gives
// the trapezoid sum of Eq. 11 over those rows, computed here independently.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

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
  EXPECT_EQ(line, "time_s,height_m,force_N,torque_Nm");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    for (auto& c : line)
      if (c == ',') c = ' ';
    std::istringstream r(line);
    Row x{};
    if (r >> x.t >> x.h >> x.f >> x.m) rows.push_back(x);
  }
  return rows;
}

double param(const Scenario& sc, const std::string& name) { return sc.parameters.at(name); }
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
  fs::remove_all(out);
}
