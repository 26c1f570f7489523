// Every shipped scene that states its parcel count (checks.particle_count) starts its coupled run
// with all of them, with the real solvers: a scene whose particle script places its parcels
// only during the run (settling-bed's pour, once) or one loose pour of which cannot hold them
// (ft4-rheometer's quick size: 1,912 of 1,920) used to stop before its first step. Two coupling
// steps each; the paper sizes (minutes to hours of settling) are left to docs/.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {
struct Shipped {
  const char* scene;
  double parcels;  // computed here from the scene's description, not read from it
};

// round(mass / (rho_p pi/6 d^3)) where a scene states its powder's mass, else its stated count
// (MCC at 1750 kg/m3 in parcels of 3 mm, cg 10)
double parcelsOf(double mass) {
  return std::round(mass / (1750 * std::numbers::pi / 6 * 3e-3 * 3e-3 * 3e-3));
}
const double kFt4Quick = parcelsOf(0.0475);   // 47.5 g: 1,920
const double kSpoutQuick = parcelsOf(0.100);  // 0.1 kg: 4,042

class ShippedScene : public ::testing::TestWithParam<Shipped> {};

TEST_P(ShippedScene, StartsWithEveryParcelItStates) {
  const Shipped s = GetParam();
  const auto scene = fs::path(COSIM_SOURCE_DIR) / "scenarios" / s.scene;
  const Scenario probe = loadScenario(scene);
  ASSERT_TRUE(probe.checks.particle_count.has_value()) << s.scene;
  EXPECT_EQ(static_cast<double>(*probe.checks.particle_count), s.parcels) << s.scene;

  std::string name = s.scene;
  for (auto& c : name)
    if (c == '/' || c == '.') c = '-';
  RunOptions o;
  o.quiet = true;
  o.output = fs::temp_directory_path() / ("cosim-shipped-" + name + "-" + std::to_string(getpid()));
  fs::remove_all(o.output);
  const std::string end = "coupling.end_time=" + std::to_string(2 * probe.coupling.dt);
  RunResult r = Coupler(loadScenario(scene, {end}), o).run();
  ASSERT_EQ(r.exit_code, 0) << s.scene << ": " << r.message;
  EXPECT_EQ(static_cast<double>(r.final_state.ids.size()), s.parcels) << s.scene;
  fs::remove_all(o.output);
}

INSTANTIATE_TEST_SUITE_P(CountedScenes, ShippedScene,
                         ::testing::Values(Shipped{"settling-bed/scenario.yaml", 1000},
                                           Shipped{"ft4-rheometer/scenario.yaml", kFt4Quick},
                                           Shipped{"fluidized-bed/scenario.yaml", 1000},
                                           Shipped{"fluidized-cylinder/scenario.yaml", 1000},
                                           Shipped{"plasma-coating-bed/scenario.yaml", 4000},
                                           Shipped{"spout-2d/scenario.yaml", kSpoutQuick}),
                         [](const ::testing::TestParamInfo<Shipped>& info) {
                           std::string n = info.param.scene;
                           n = n.substr(0, n.find('/'));
                           std::string out;
                           for (char c : n) out += (c == '-') ? '_' : c;
                           return out;
                         });
}  // namespace
