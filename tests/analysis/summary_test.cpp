#include "cosim/analysis/summary.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fs = std::filesystem;
using namespace cosim::analysis;

namespace {

fs::path tempFile(const std::string& name) {
  return fs::temp_directory_path() / ("cosim_" + name + "_" + std::to_string(::getpid()) + ".json");
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Summary example() {
  Summary s;
  s.scenario = "plasma-coating-bed";
  s.run_id = "r1";
  s.status = "running";
  s.start_time = 0.0;
  s.end_time = 0.1 + 0.2;  // not a short decimal: must come back exactly
  s.steps = 5000;
  s.headline = {{"coating_on_particles_kg", 1.25e-6},
                {"mass_balance_error_percent", std::nan("")},
                {"particle_count", 4000}};
  s.timings = {{"total", 12.5}, {"fluid_compute", 3.25}};
  s.parameters = {{"flow_lpm", 100}, {"u_up", -1.5e-3}};
  s.coupling_dt = 1e-4;
  s.dem_steps = 10;
  s.cg = 5;
  s.coating = true;
  s.observables = {{"v", -0.0125, "", -0.0124, 0.008},
                   {"cv", std::nan(""), "the mean coating is 0", std::nullopt, std::nullopt}};
  return s;
}

}  // namespace

TEST(Summary, WritesTheKeysReadersExpectAndReplacesAtomically) {
  const fs::path path = tempFile("summary_keys");
  Summary s = example();
  writeSummary(path, s);
  s.status = "completed";
  s.message = "line1\n\"quoted\"";
  writeSummary(path, s);  // rewritten in place
  const std::string j = slurp(path);
  EXPECT_NE(j.find("\"format\": \"cosim-summary\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"status\": \"completed\""), std::string::npos) << j;  // scripts/sweep-flows.sh
  EXPECT_NE(j.find("\"message\": \"line1\\n\\\"quoted\\\"\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"coating_on_particles_kg\": 1.25e-06"), std::string::npos) << j;
  EXPECT_NE(j.find("\"mass_balance_error_percent\": null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"total\": 12.5"), std::string::npos) << j;
  EXPECT_NE(j.find("\"steps\": 5000"), std::string::npos) << j;
  EXPECT_NE(j.find("\"dem_steps\": 10"), std::string::npos) << j;
  EXPECT_NE(j.find("\"undefined\": \"the mean coating is 0\""), std::string::npos) << j;
  // The layout readers rely on: extra.parameters, extra.observables.<name>.value, timings_s.total.
  const Json parsed = Json::parse(j);
  EXPECT_EQ(parsed.at("extra").at("parameters").at("flow_lpm").get<double>(), 100.0);
  EXPECT_EQ(parsed.at("extra").at("observables").at("v").at("value").get<double>(), -0.0125);
  EXPECT_FALSE(parsed.at("extra").at("observables").at("cv").contains("value"));
  EXPECT_EQ(parsed.at("timings_s").at("total").get<double>(), 12.5);
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  fs::remove(path);
  EXPECT_THROW(writeSummary("/nonexistent-dir/summary.json", s), std::runtime_error);
}

TEST(Summary, RoundTripsThroughTheFileExactly) {
  const fs::path path = tempFile("summary_round_trip");
  Summary s = example();
  s.message = "participant 'fluid': \xff not UTF-8";  // a log tail may hold any bytes
  writeSummary(path, s);
  const Summary back = readSummary(path);
  fs::remove(path);
  EXPECT_EQ(back.scenario, s.scenario);
  EXPECT_EQ(back.run_id, s.run_id);
  EXPECT_EQ(back.status, s.status);
  EXPECT_NE(back.message.find("participant 'fluid': "), std::string::npos);  // bad byte replaced
  EXPECT_EQ(back.start_time, s.start_time);
  EXPECT_EQ(back.end_time, s.end_time);  // bit for bit
  EXPECT_EQ(back.steps, s.steps);
  ASSERT_EQ(back.headline.size(), s.headline.size());
  for (std::size_t i = 0; i < s.headline.size(); ++i) {
    EXPECT_EQ(back.headline[i].first, s.headline[i].first);  // order kept
    if (std::isnan(s.headline[i].second))
      EXPECT_TRUE(std::isnan(back.headline[i].second));  // null reads back as NaN
    else
      EXPECT_EQ(back.headline[i].second, s.headline[i].second);
  }
  EXPECT_EQ(back.timings, s.timings);
  EXPECT_EQ(back.parameters, s.parameters);
  EXPECT_EQ(back.coupling_dt, s.coupling_dt);
  EXPECT_EQ(back.dem_steps, s.dem_steps);
  EXPECT_EQ(back.cg, s.cg);
  EXPECT_EQ(back.coating, s.coating);
  ASSERT_EQ(back.observables.size(), 2u);
  EXPECT_EQ(back.observables[0].name, "v");
  EXPECT_EQ(back.observables[0].value, -0.0125);
  EXPECT_EQ(back.observables[0].undefined, "");
  EXPECT_EQ(back.observables[0].reference, std::optional<double>(-0.0124));
  EXPECT_EQ(back.observables[0].relative_error, std::optional<double>(0.008));
  EXPECT_EQ(back.observables[1].name, "cv");
  EXPECT_TRUE(std::isnan(back.observables[1].value));
  EXPECT_EQ(back.observables[1].undefined, "the mean coating is 0");
  EXPECT_FALSE(back.observables[1].reference);
  // In memory too (to_json / from_json).
  const Summary valid = example();
  EXPECT_EQ(Json(Json(valid).get<Summary>()).dump(), Json(valid).dump());
}

TEST(Summary, ReadingRefusesWhatIsNotASummaryAndNamesTheFile) {
  const fs::path path = tempFile("summary_bad");
  for (const char* text : {"{\"status\": \"completed\"", "{\"format\": \"cosim-report\"}",
                           "{\"format\": \"cosim-summary\", \"status\": \"completed\"}"}) {
    std::ofstream(path) << text;
    try {
      readSummary(path);
      ADD_FAILURE() << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
  fs::remove(path);
  EXPECT_THROW(readSummary(path), std::runtime_error);  // missing
}
