// Options of the liggghts adapter: defaults, and errors that name the key and what to write.
#include "cosim/liggghts/adapter_options.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using cosim::liggghts::AdapterOptions;
using cosim::liggghts::DtCheckPolicy;

namespace {
std::string errorOf(const std::string& yaml) {
  try {
    AdapterOptions::parse(yaml);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(AdapterOptions, DefaultsAndValues) {
  const auto o = AdapterOptions::parse("script: in.bed\n");
  EXPECT_EQ(o.script, "in.bed");
  EXPECT_DOUBLE_EQ(o.impact_speed, 2.0);
  EXPECT_EQ(o.dt_check, DtCheckPolicy::refuse);
  const auto p = AdapterOptions::parse("{script: a, impact_speed: 0.5, dt_check: warn}");
  EXPECT_DOUBLE_EQ(p.impact_speed, 0.5);
  EXPECT_EQ(p.dt_check, DtCheckPolicy::warn);
  EXPECT_EQ(AdapterOptions::parse("{script: a, dt_check: off}").dt_check, DtCheckPolicy::off);
}

TEST(AdapterOptions, ErrorsNameTheKey) {
  EXPECT_NE(errorOf("").find("needs at least `script:"), std::string::npos);
  EXPECT_NE(errorOf("impact_speed: 1").find("options.script: missing"), std::string::npos);
  EXPECT_NE(
      errorOf("{script: a, impact_speed: -1}").find("options.impact_speed: must be a positive"),
      std::string::npos);
  EXPECT_NE(
      errorOf("{script: a, impact_speed: fast}").find("options.impact_speed: expected a number"),
      std::string::npos);
  EXPECT_NE(errorOf("{script: a, dt_check: maybe}").find("'maybe' is not one of refuse, warn, off"),
            std::string::npos);
  EXPECT_NE(errorOf("{script: a, scrpit: b}").find("options.scrpit: unknown option"),
            std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("must be a mapping"), std::string::npos);
  EXPECT_NE(errorOf("script: [a").find("not valid YAML"), std::string::npos);
}
