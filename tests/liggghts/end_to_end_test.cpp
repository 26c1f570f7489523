// End to end with the orchestrator: a LIGGGHTS particle in the analytic fluid adapter
// (tests/liggghts/data/settling-sphere-liggghts: the settling-sphere scene with the particles
// participant swapped to LIGGGHTS) reaches its terminal velocity within 0.5 %, and follows the
// analytic transient.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "cosim/link/fields.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {
// Independent reference: Stokes drag + buoyancy, released at rest.
// d = 1.5 mm, rho_p = 2500, rho_f = 1260, mu = 1 Pa s:
//   v_t = 1240 * 9.81 * 2.25e-6 / 18 = 1.52055e-3 m/s, tau = 2500 * 2.25e-6 / 18 = 3.125e-4 s.
constexpr double kVt = 1240 * 9.81 * 2.25e-6 / 18;
constexpr double kTau = 2500 * 2.25e-6 / 18;
}  // namespace

TEST(LiggghtsEndToEnd, SphereReachesTerminalVelocityInAnalyticFluid) {
  Scenario sc = loadScenario(fs::path(COSIM_LIGGGHTS_TEST_DATA) / "settling-sphere-liggghts" /
                             "scenario.yaml");
  RunOptions o;
  o.quiet = true;
  o.output = fs::temp_directory_path() / ("cosim-liggghts-e2e-" + std::to_string(getpid()));
  fs::remove_all(o.output);
  Coupler c(std::move(sc), o);
  std::vector<double> t, vz;
  c.on_step = [&](double time, const link::ParticleData& s) {
    if (s.size() == 1) {
      t.push_back(time);
      vz.push_back(s.get(field::velocity)[2]);
    }
  };
  const RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;
  ASSERT_EQ(r.final_state.size(), 1u);
  const double v_end = r.final_state.get(field::velocity)[2];
  EXPECT_NEAR(v_end, -kVt, 0.005 * kVt);  // 6 ms = 19 tau
  // transient at every reported time: v(t) = -v_t (1 - exp(-t/tau)), within 1 % of v_t
  ASSERT_FALSE(t.empty());
  double worst = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double ref = -kVt * (1 - std::exp(-t[k] / kTau));
    EXPECT_NEAR(vz[k], ref, 0.01 * kVt) << "t = " << t[k];
    worst = std::max(worst, std::abs(vz[k] - ref) / kVt);
  }
  std::printf(
      "terminal velocity %.6e m/s (analytic %.6e), relative error %.2e; %zu steps, worst "
      "transient error %.2e v_t\n",
      v_end, -kVt, std::abs(v_end + kVt) / kVt, t.size(), worst);
  fs::remove_all(o.output);
}

// A script whose own `run` outlasts participants.particles.timeout: the run says whom it waits
// for after 15 s, stops at step 0 and the message shows the adapter's log naming where LIGGGHTS
// writes its progress meanwhile (it used to show an empty log).
TEST(LiggghtsEndToEnd, AScriptOutlastingTheTimeoutSaysWhomItAwaitsAndWhereLiggghtsWrites) {
  const fs::path dir =
      fs::temp_directory_path() / ("cosim-liggghts-slow-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(fs::path(COSIM_LIGGGHTS_TEST_DATA) / "settling-sphere-liggghts", dir / "scene",
           fs::copy_options::recursive);
  {
    std::FILE* f = std::fopen((dir / "scene" / "dem" / "in.sphere").c_str(), "a");
    ASSERT_NE(f, nullptr);
    std::fputs("\nrun 100000000\n", f);  // minutes of LIGGGHTS before the first coupled step
    std::fclose(f);
  }
  Scenario sc =
      loadScenario(dir / "scene" / "scenario.yaml", {"participants.particles.timeout=17"});
  RunOptions o;
  o.quiet = true;
  o.output = dir / "run";
  Coupler c(std::move(sc), o);
  const RunResult r = c.run();
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.message.find("did not answer within 17 s at step 0"), std::string::npos) << r.message;
  const std::string liggghts_log = (o.output / "particles" / "liggghts.log").string();
  EXPECT_NE(r.message.find("LIGGGHTS' own output meanwhile: " + liggghts_log), std::string::npos)
      << r.message;
  // While it waited, the run said who it waited for and where to look (after 15 s)
  std::ifstream log(o.output / "cosim.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("waiting 15 s for the first answer of particles (its log: " +
                      (o.output / "particles.log").string()),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("gives up after 17 s (participants.particles.timeout)"), std::string::npos)
      << text;
  fs::remove_all(dir);
}
