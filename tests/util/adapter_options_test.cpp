// The adapters' option reader: each kind of value, each error naming the scenario key, what was
// expected and what was given.
#include "cosim/util/adapter_options.h"

#include <gtest/gtest.h>

#include "cosim/util/errors.h"

using cosim::util::AdapterOptions;
using cosim::util::OptionSpec;

namespace {

const std::vector<OptionSpec> kSpecs = {
    {"speed", "1", "[m/s]"},       {"count", "3", "whole"},        {"mode", "a", "a | b"},
    {"on", "false", "switch"},     {"origin", "[0, 0, 0]", "[m]"}, {"patches", "[inlet]", "names"},
    {"name", "required", "a text"}};

AdapterOptions read(const std::string& yaml) {
  return AdapterOptions(yaml, "fluid", "test-adapter", kSpecs, "docs/x.md");
}

// The message of what `f` throws; it must be an input error (exit code 1).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const cosim::InputError& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

}  // namespace

TEST(AdapterOptions, ValuesAndDefaults) {
  const auto o = read(
      "{speed: 2.5, count: 4, mode: b, on: true, origin: [1, 2, 3], "
      "patches: top, name: x}");
  EXPECT_EQ(o.number("speed", 1, 0, 10), 2.5);
  EXPECT_EQ(o.whole("count", 3, 1, 9), 4);
  EXPECT_EQ(o.choice("mode", "a", {"a", "b"}), "b");
  EXPECT_TRUE(o.flag("on", false));
  EXPECT_EQ(o.vec3("origin", {0, 0, 0}), (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(o.names("patches", {"inlet"}), std::vector<std::string>{"top"});
  EXPECT_EQ(o.requiredText("name", "x"), "x");
  const auto d = read("");
  EXPECT_EQ(d.number("speed", 1), 1);
  EXPECT_EQ(d.whole("count", 3, 1, 9), 3);
  EXPECT_EQ(d.names("patches", {"inlet", "side"}), (std::vector<std::string>{"inlet", "side"}));
  EXPECT_TRUE(d.empty());
  EXPECT_EQ(read("patches: [a, b]").names("patches", {}), (std::vector<std::string>{"a", "b"}));
}

TEST(AdapterOptions, ErrorsNameTheScenarioKeyTheExpectedAndTheGiven) {
  const std::string key = "scenario participants.fluid.options.";
  EXPECT_EQ(errorOf([] { read("{spede: 1}"); }),
            key +
                "spede: unknown option of test-adapter; it knows speed, count, mode, on, "
                "origin, patches, name (docs/x.md)");
  EXPECT_EQ(errorOf([] { read("speed: fast").number("speed", 1); }),
            key + "speed: expected a number, got 'fast'");
  EXPECT_EQ(errorOf([] { read("speed: .nan").number("speed", 1); }),
            key + "speed: expected a number, got '.nan'");
  EXPECT_EQ(errorOf([] { read("speed: 20").number("speed", 1, 0, 10); }),
            key + "speed: expected a value in [0, 10], got 20");
  EXPECT_EQ(errorOf([] { read("speed: 0").positive("speed", 1); }),
            key + "speed: expected a number > 0, got 0");
  EXPECT_EQ(errorOf([] { read("count: 2.5").whole("count", 3, 1, 9); }),
            key + "count: expected a whole number from 1 to 9, got 2.5");
  EXPECT_EQ(errorOf([] {
              read("mode: c").choice("mode", "a", {"a", "b"});
            }),
            key + "mode: expected one of a, b, got 'c'");
  EXPECT_EQ(errorOf([] { read("on: maybe").flag("on", false); }),
            key + "on: expected true or false, got 'maybe'");
  EXPECT_EQ(errorOf([] {
              read("origin: [1, 2]").vec3("origin", {0, 0, 0});
            }),
            key + "origin: expected three numbers [x, y, z], got '[1, 2]'");
  EXPECT_EQ(errorOf([] { read("patches: {a: 1}").names("patches", {}); }),
            key + "patches: expected a name or a list of names, got '{a: 1}'");
  EXPECT_EQ(errorOf([] { read("").requiredText("name", "bed"); }),
            key + "name: missing; test-adapter needs it, e.g. `name: bed`");
  EXPECT_EQ(errorOf([] { read("[1, 2]"); }),
            "scenario participants.fluid.options: expected a map of options (key: value), got "
            "'[1, 2]'");
  EXPECT_NE(errorOf([] { read("speed: [1"); }).find("options: not valid YAML"), std::string::npos);
}

TEST(AdapterOptions, TheTableHasARowPerOptionWithItsBarsEscaped) {
  const std::string t = cosim::util::optionsTable(kSpecs);
  EXPECT_EQ(t.rfind("| option | default | meaning |\n|---|---|---|\n| `speed` | 1 | [m/s] |\n", 0),
            0u)
      << t;
  EXPECT_NE(t.find("| `mode` | a | a \\| b |\n"), std::string::npos) << t;
}
