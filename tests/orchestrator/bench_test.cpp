// cosim bench on the analytic settling sphere: the three stages run and the last line reads
// `coupled/max(dem,cfd) = R; serial share = S %` with R, S positive and finite. No timing is
// asserted (the machine may be loaded).
#include "bench.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
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

// Runs `cmd` (stderr with stdout), returns its output; `status` its exit status.
std::string capture(const std::string& cmd, int& status) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  std::string text;
  if (p == nullptr) {
    status = -1;
    return text;
  }
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) text += buf;
  status = pclose(p);
  return text;
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

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
  const models::SceneModels models = makeModels(sc);
  const Plan plan = makePlan(sc, models);
  auto rec = std::make_shared<TermsRecording>();
  for (int k = 0; k < 3; ++k) {
    models::CouplingTerms t;
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

// --peer: the coupled step once more on the rank-to-rank data path, timed on a line of its own
// before the last; the sphere settles there exactly as on the central path (same laws, same
// samples: docs/design.md section 5), so the two stages end in the same state.
TEST(Bench, PeerStageTimesTheRankToRankPathOnALineOfItsOwn) {
  const fs::path out = fs::temp_directory_path() / ("cosim-bench-peer-" + std::to_string(getpid()));
  fs::remove_all(out);
  int status = 0;
  const std::string text =
      capture(std::string(COSIM_EXE) + " bench " + COSIM_SOURCE_DIR +
                  "/scenarios/settling-sphere --steps 4 --warmup 1 --peer -o " + out.string(),
              status);
  ASSERT_EQ(status, 0) << text;
  const std::regex peer_line(
      R"((^|\n)peer/max\(dem,cfd\) = [0-9]+\.[0-9]+; serial share = [0-9]+\.[0-9]+ %\n)");
  EXPECT_TRUE(std::regex_search(text, peer_line)) << text;
  EXPECT_TRUE(std::regex_match(
      lastLine(text), std::regex(R"(coupled/max\(dem,cfd\) = [0-9.]+; serial share = [0-9.]+ %)")))
      << text;
  EXPECT_NE(text.find("\npeer "), std::string::npos) << text;  // its row of the table
  const auto coupled = nlohmann::json::parse(fileText(out / "coupled" / "summary.json"));
  const auto peer = nlohmann::json::parse(fileText(out / "peer" / "summary.json"));
  EXPECT_EQ(peer.at("steps"), coupled.at("steps"));
  // on the peer path the particles sample the gas themselves, and time it
  EXPECT_TRUE(peer.at("timings_s").contains("particles_sample_compute")) << peer.dump(1);
  EXPECT_FALSE(coupled.at("timings_s").contains("particles_sample_compute")) << coupled.dump(1);
  EXPECT_EQ(peer.at("headline"), coupled.at("headline")) << peer.dump(1);
  EXPECT_EQ(peer.at("extra").at("observables"), coupled.at("extra").at("observables"))
      << peer.dump(1);
  fs::remove_all(out);
}

// A run keeps the data path it began with, so --from takes no peer stage: refused before any
// stage runs, naming the flag and what to do instead.
TEST(Bench, PeerStageFromARunIsRefusedNamingTheFlag) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-bench-peerfrom-" + std::to_string(getpid()));
  fs::remove_all(out);
  int status = 0;
  const std::string text = capture(std::string(COSIM_EXE) + " bench --from " + out.string() +
                                       "/nowhere --peer -o " + (out / "bench").string(),
                                   status);
  EXPECT_NE(status, 0) << text;
  EXPECT_NE(text.find("--peer"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(out / "bench")) << text;
}

// A scene without a fluid has no per-parcel exchange and no peer path: --peer is refused saying so.
TEST(Bench, PeerStageWithoutAFluidIsRefusedSayingWhy) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-bench-nofluid-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  std::ofstream(base / "scene.yaml") << R"(name: alone
participants:
  particles:
    adapter: free-particles
    options:
      density: 2500
      particles: [ { id: 1, position: [0, 0, 0], velocity: [0, 0, 0], radius: 1.0e-4 } ]
coupling: { dt: 1.0e-4, dem_steps: 1, end_time: 1.0e-3 }
)";
  int status = 0;
  const std::string text =
      capture(std::string(COSIM_EXE) + " bench " + (base / "scene.yaml").string() +
                  " --steps 2 --warmup 1 --peer -o " + (base / "b").string(),
              status);
  EXPECT_NE(status, 0) << text;
  EXPECT_NE(text.find("no fluid participant"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(base / "b")) << text;
  fs::remove_all(base);
}

// --from RUN: each stage continues a copy of the run's newest checkpoint for warmup + steps
// coupling steps (the settling sphere at dt 1e-4 s from its checkpoint at 2 ms: 50 steps before,
// 1 + 4 after); the run's own folder is not written.
TEST(Bench, FromARunContinuesCopiesOfItsNewestCheckpoint) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-bench-from-" + std::to_string(getpid()));
  fs::remove_all(base);
  const fs::path run = base / "run", out = base / "bench";
  int status = 0;
  const std::string scene = std::string(COSIM_SOURCE_DIR) + "/scenarios/settling-sphere";
  std::string text = capture(std::string(COSIM_EXE) + " run " + scene + " -q -o " + run.string() +
                                 " --set coupling.end_time=0.002 --set checkpoint.interval=0.001",
                             status);
  ASSERT_EQ(status, 0) << text;
  const std::string summary_before = fileText(run / "summary.json");
  const std::string series_before = fileText(run / "timeseries.csv");

  text = capture(std::string(COSIM_EXE) + " bench --from " + run.string() +
                     " --steps 4 --warmup 1 -o " + out.string(),
                 status);
  ASSERT_EQ(status, 0) << text;
  EXPECT_NE(text.find("from " + run.string() + " at t = 0.002 s"), std::string::npos) << text;
  for (const char* stage : {"dem", "cfd", "coupled"}) {
    const auto summary = nlohmann::json::parse(fileText(out / stage / "summary.json"));
    EXPECT_EQ(summary.at("steps").get<int>(), 25) << stage;
    EXPECT_NEAR(summary.at("end_time_s").get<double>(), 0.0025, 1e-12) << stage;
  }
  std::smatch m;
  const std::string last = lastLine(text);
  EXPECT_TRUE(std::regex_match(
      last, m, std::regex(R"(coupled/max\(dem,cfd\) = [0-9.]+; serial share = [0-9.]+ %)")))
      << text;
  EXPECT_EQ(fileText(run / "summary.json"), summary_before);
  EXPECT_EQ(fileText(run / "timeseries.csv"), series_before);

  // A scenario beside --from, or a run without a checkpoint: refused with the reason.
  text = capture(std::string(COSIM_EXE) + " bench " + scene + " --from " + run.string(), status);
  EXPECT_NE(status, 0) << text;
  EXPECT_NE(text.find("excludes"), std::string::npos) << text;
  const fs::path bare = base / "bare";
  capture(std::string(COSIM_EXE) + " run " + scene + " -q -o " + bare.string() +
              " --set coupling.end_time=0.001 --set checkpoint.interval=0",
          status);
  ASSERT_EQ(status, 0);
  text = capture(std::string(COSIM_EXE) + " bench --from " + bare.string(), status);
  EXPECT_NE(status, 0) << text;
  EXPECT_NE(text.find("no complete checkpoint"), std::string::npos) << text;
  fs::remove_all(base);
}
