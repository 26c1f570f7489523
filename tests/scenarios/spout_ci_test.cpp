// The pseudo-2D spout with the real solvers (OpenFOAM + LIGGGHTS through the orchestrator) at
// its CI size, then `cosim piv` on the run: the pipeline yields the PIV grid and the profiles at
// 13 and 15 cm, and a spout has formed: over the whole depth, parcels rise through the middle
// and fall at the sides.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cosim/analysis/piv_command.h"
#include "cosim/analysis/piv_compare.h"
#include "cosim/analysis/report.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

TEST(SpoutCi, JetCarriesParcelsUpTheMiddleAndPivYieldsTheProfiles) {
  const fs::path out = fs::temp_directory_path() / ("cosim-spout-ci-" + std::to_string(getpid()));
  fs::remove_all(out);
  Scenario sc = loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/spout-2d/ci.yaml");
  RunOptions o;
  o.quiet = true;
  o.output = out;
  Coupler c(std::move(sc), o);
  RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  // 0.02 kg of 3 mm parcels of 1750 kg/m3: 0.02 / (1750 pi/6 0.003^3) = 808.4
  ASSERT_EQ(r.final_state.size(), 808u);
  // The jet meets the packed bed in the first step: the gas through the parcels above the
  // nozzle is faster than 26.7 m/s and the fluid reports a Courant number above 1, which cosim
  // warns about once and runs on (that warning once crashed the orchestrator).
  {
    std::ifstream log(out / "cosim.log");
    std::stringstream text;
    text << log.rdbuf();
    EXPECT_NE(text.str().find("warning: fluid Courant number"), std::string::npos)
        << "the first step's Courant warning is gone: the test no longer covers that path";
  }

  // As a user runs it: the scene's window and discarded time, the profiles at 13 and 15 cm.
  cosim::analysis::PivCommandOptions piv;
  piv.run = out;
  std::ostringstream text;
  ASSERT_EQ(cosim::analysis::runPivCommand(piv, text), 0);
  const auto profiles = cosim::analysis::readProfileCsv(out / "piv" / "profiles.csv");
  // 100 mm wide in 4 mm bins: 25 bins per height
  ASSERT_EQ(profiles.size(), 50u) << text.str();
  EXPECT_DOUBLE_EQ(profiles.front().height, 0.13);
  EXPECT_DOUBLE_EQ(profiles.back().height, 0.15);
  EXPECT_TRUE(fs::exists(out / "piv" / "grid.csv"));
  std::string why;
  if (cosim::analysis::findPython(why))
    EXPECT_TRUE(fs::exists(out / "piv" / "piv.png")) << text.str();

  // The spout, seen over the whole depth (25 mm) in 12.5 mm bins at 62.5 and 87.5 mm, averaged
  // over 0.1 .. 0.2 s: the two middle bins rise, the two outermost fall.
  piv.depth = 0.025;
  piv.cell = 0.0125;
  piv.heights = {0.0625, 0.0875};
  piv.output = out / "piv-depth";
  ASSERT_EQ(cosim::analysis::runPivCommand(piv, text), 0);
  std::map<double, std::map<double, double>> vz;  // height -> x -> vz
  for (const auto& p : cosim::analysis::readProfileCsv(out / "piv-depth" / "profiles.csv"))
    vz[p.height][p.x] = p.vz;
  for (const auto& [h, row] : vz) {
    double middle = 0, sides = 0;
    int nm = 0, ns = 0;
    for (const auto& [x, v] : row) {
      if (std::fabs(x) < 0.0125 && std::isfinite(v)) middle += v, ++nm;
      if (std::fabs(x) > 0.0375 && std::isfinite(v)) sides += v, ++ns;
    }
    ASSERT_GT(nm, 0) << "no parcel in the middle at z = " << h;
    ASSERT_GT(ns, 0) << "no parcel at the sides at z = " << h;
    std::printf("spout at z = %.1f mm: middle %.2f m/s, outer bins %.2f m/s\n", 1e3 * h,
                middle / nm, sides / ns);
    EXPECT_GT(middle / nm, 0.5) << "no spout at z = " << h << "\n" << text.str();
    EXPECT_LT(sides / ns, 0.0) << "the sides do not fall at z = " << h << "\n" << text.str();
  }
  fs::remove_all(out);
}
