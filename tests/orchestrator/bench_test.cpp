// cosim bench on the analytic settling sphere: the three stages run and the last line reads
// `coupled/max(dem,cfd) = R; serial share = S %` with R, S positive and finite. No timing is
// asserted (the machine may be loaded).
#include "bench.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>

#include "cosim/link/fields.h"
#include "coupling_scheme.h"
#include "plan.h"
#include "scenario.h"

namespace fs = std::filesystem;
using namespace cosim;
using namespace cosim::orchestrator;

namespace {

std::string lastLine(const std::string& text) {
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

}  // namespace

TEST(Bench, RatiosByHand) {
  std::map<std::string, BenchStage> s;
  s["dem"].phases = {{"advance", 0.010}, {"bookkeeping", 0.001}};
  s["cfd"].phases = {{"advance", 0.020}};
  s["coupled"].phases = {
      {"fluid_sample", 0.004}, {"models", 0.001}, {"advance", 0.020}, {"bookkeeping", 0.0}};
  const BenchRatios r = benchRatios(s);
  EXPECT_DOUBLE_EQ(r.coupled_over_max, 0.025 / 0.020);
  EXPECT_DOUBLE_EQ(r.serial_percent, 100.0 * 0.005 / 0.025);
}

// The solver-alone stages replay the coupled stage's terms interval by interval, by particle id,
// and hold the last interval's terms (coating no longer paid) past the recording's end.
TEST(Bench, AloneStageReplaysTheRecordedIntervalsById) {
  const Scenario sc = loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios" / "settling-sphere");
  const SceneModels models = makeModels(sc);
  const Plan plan = makePlan(sc, models);
  auto rec = std::make_shared<TermsRecording>();
  for (int k = 0; k < 3; ++k) {
    CouplingTerms t;
    t.forcing.ids = {7, 9};
    t.forcing.field(field::drag_coefficient) = {1.0 + k, 10.0 + k};
    t.forcing.field(field::coating_increment) = {0.5, 0.25};
    t.exchange.ids = {7, 9};
    t.exchange.field(field::drag_coefficient) = {100.0 + k, 200.0 + k};
    rec->push_back(t);
  }
  FrozenScheme alone(sc, plan, FrozenScheme::Alone::particles, rec);
  link::ParticleData state;
  state.ids = {9, 7};  // another order than the recording's
  for (int k = 0; k < 3; ++k) {
    const auto t = alone.replay(state);
    ASSERT_TRUE(t.has_value()) << "interval " << k;
    EXPECT_EQ(t->forcing.ids, state.ids);
    EXPECT_EQ(t->forcing.get(field::drag_coefficient), (std::vector<double>{10.0 + k, 1.0 + k}));
    EXPECT_EQ(t->forcing.get(field::coating_increment), (std::vector<double>{0.25, 0.5}));
  }
  FrozenScheme fluid(sc, plan, FrozenScheme::Alone::fluid, rec);
  EXPECT_FALSE(fluid.replay(state).has_value());  // samples once: the fluid places the parcels
  for (int k = 1; k < 3; ++k) {
    const auto t = fluid.replay(state);
    ASSERT_TRUE(t.has_value()) << "interval " << k;
    EXPECT_EQ(t->exchange.get(field::drag_coefficient),
              (std::vector<double>{100.0 + k, 200.0 + k}));
  }
  const auto past = alone.replay(state);
  ASSERT_TRUE(past.has_value());
  EXPECT_EQ(past->forcing.get(field::drag_coefficient), (std::vector<double>{12.0, 3.0}));
  EXPECT_EQ(past->forcing.get(field::coating_increment), (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(alone.replayedIntervals(), 3u);

  FrozenScheme unrecorded(sc, plan, FrozenScheme::Alone::particles);
  EXPECT_FALSE(unrecorded.replay(state).has_value());  // the first interval samples as usual
}

TEST(Bench, CommandLastLineOnTheSettlingSphere) {
  const fs::path out = fs::temp_directory_path() / ("cosim-bench-" + std::to_string(getpid()));
  fs::remove_all(out);
  const std::string cmd = std::string(COSIM_EXE) + " bench " + COSIM_SOURCE_DIR +
                          "/scenarios/settling-sphere --steps 4 --warmup 1 -o " + out.string() +
                          " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) text += buf;
  ASSERT_EQ(pclose(p), 0) << text;
  for (const char* stage : {"dem", "cfd", "coupled"}) {
    EXPECT_TRUE(fs::exists(out / stage / "summary.json")) << stage;
    EXPECT_NE(text.find(std::string("\n") + stage + " "), std::string::npos) << text;
  }
  const std::regex format(
      R"(coupled/max\(dem,cfd\) = ([0-9]+(\.[0-9]+)?); serial share = ([0-9]+(\.[0-9]+)?) %)");
  std::smatch m;
  const std::string last = lastLine(text);
  ASSERT_TRUE(std::regex_match(last, m, format)) << "last line: " << last << "\n" << text;
  const double ratio = std::stod(m[1]);
  const double serial = std::stod(m[3]);
  EXPECT_TRUE(std::isfinite(ratio) && ratio > 0) << last;
  EXPECT_TRUE(std::isfinite(serial) && serial > 0 && serial <= 100) << last;
  fs::remove_all(out);
}
