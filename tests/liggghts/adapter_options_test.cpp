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
  EXPECT_NE(errorOf("").find("options.script: missing; the liggghts adapter needs at least "
                             "`script:"),
            std::string::npos)
      << errorOf("");
  EXPECT_NE(errorOf("impact_speed: 1").find("participants.particles.options.script: missing"),
            std::string::npos)
      << errorOf("impact_speed: 1");
  EXPECT_NE(errorOf("{script: a, impact_speed: -1}")
                .find("options.impact_speed: expected a number > 0, got -1"),
            std::string::npos);
  EXPECT_NE(errorOf("{script: a, impact_speed: fast}")
                .find("options.impact_speed: expected a number, got 'fast'"),
            std::string::npos);
  EXPECT_NE(errorOf("{script: a, dt_check: maybe}")
                .find("options.dt_check: expected one of refuse, warn, off, got 'maybe'"),
            std::string::npos);
  EXPECT_NE(errorOf("{script: a, scrpit: b}")
                .find("options.scrpit: unknown option of cosim-liggghts; it knows script, "
                      "impact_speed, dt_check (docs/liggghts.md)"),
            std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("expected a map of options"), std::string::npos);
  EXPECT_NE(errorOf("script: [a").find("not valid YAML"), std::string::npos);
  EXPECT_NE(errorOf("script: [a, b]").find("options.script: expected a text, got '[a, b]'"),
            std::string::npos)
      << errorOf("script: [a, b]");
}
