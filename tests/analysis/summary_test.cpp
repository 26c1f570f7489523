#include "cosim/analysis/summary.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace cosim::analysis;

TEST(Summary, WritesHeadlineNumbersTimingsAndReplacesAtomically) {
  const fs::path path = fs::temp_directory_path() / ("cosim_summary_" + std::to_string(::getpid()) + ".json");
  Summary s;
  s.scenario = "plasma-coating-bed";
  s.run_id = "r1";
  s.status = "running";
  s.end_time = 0.5;
  s.steps = 5000;
  s.headline = {{"coating_on_particles_kg", 1.25e-6}, {"mass_balance_error_percent", std::nan("")}};
  s.timings = {{"total", 12.5}};
  s.extra = Json::object();
  s.extra["parameters"]["flow_lpm"] = 100;
  writeSummary(path, s);
  s.status = "completed";
  s.message = "line1\n\"quoted\"";
  writeSummary(path, s);  // rewritten in place
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string j = text.str();
  EXPECT_NE(j.find("\"status\": \"completed\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"message\": \"line1\\n\\\"quoted\\\"\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"coating_on_particles_kg\": 1.25e-06"), std::string::npos) << j;
  EXPECT_NE(j.find("\"mass_balance_error_percent\": null"), std::string::npos) << j;
  EXPECT_NE(j.find("\"total\": 12.5"), std::string::npos) << j;
  EXPECT_NE(j.find("\"flow_lpm\": 100"), std::string::npos) << j;
  EXPECT_NE(j.find("\"steps\": 5000"), std::string::npos) << j;
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  fs::remove(path);
  EXPECT_THROW(writeSummary("/nonexistent-dir/summary.json", s), std::runtime_error);
}
