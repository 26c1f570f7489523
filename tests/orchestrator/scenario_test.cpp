// Scenario files: templating, overrides, and one specific error per kind of mistake.
#include "scenario.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cosim/models/registry.h"
#include "expression.h"
#include "plan.h"
#include "scenario/reference.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

const char* kGood = R"(
name: good
parameters:
  d: 1.0e-4
  flow_lpm: 50
  u: ${flow_lpm / 60000 / 0.01}
participants:
  fluid: { adapter: analytic-fluid, options: { velocity: [0, 0, "${u}"] } }
  particles: { adapter: free-particles, options: { density: 2500 } }
coupling: { dt: 1.0e-4, dem_steps: 10, end_time: 0.01 }
models:
  drag: { law: stokes }
)";

Scenario parse(const std::string& text, const std::vector<std::string>& sets = {},
               const std::vector<std::string>& unsets = {}) {
  return parseScenario(text, fs::temp_directory_path() / "bad.yaml", sets, unsets);
}

// Replaces the first occurrence of `from` in the good scenario.
std::string mutate(const std::string& from, const std::string& to) {
  std::string s = kGood;
  auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  s.replace(p, from.size(), to);
  return s;
}

void expectError(const std::string& text, const std::vector<std::string>& fragments,
                 const std::vector<std::string>& sets = {},
                 const std::vector<std::string>& unsets = {}) {
  try {
    parse(text, sets, unsets);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.yaml"), std::string::npos) << "message does not name the file: " << msg;
    for (const auto& f : fragments) {
      EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' missing in: " << msg;
    }
  }
}

}  // namespace

TEST(Scenario, GoodScenarioParsesWithParametersAndExpressions) {
  Scenario sc = parse(kGood);
  EXPECT_EQ(sc.name, "good");
  EXPECT_DOUBLE_EQ(sc.coupling.dt, 1e-4);
  EXPECT_EQ(sc.coupling.dem_steps, 10u);
  EXPECT_NEAR(sc.parameters.at("u"), 50.0 / 60000.0 / 0.01, 1e-15);
  EXPECT_NEAR(sc.participants.at("fluid").options["velocity"][2].as<double>(),
              50.0 / 60000.0 / 0.01, 1e-12);
}

TEST(Scenario, SetOverridesParametersAndKeys) {
  Scenario sc = parse(kGood, {"flow_lpm=100", "coupling.end_time=0.02"});
  EXPECT_NEAR(sc.parameters.at("u"), 100.0 / 60000.0 / 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(sc.coupling.end_time, 0.02);
}

// A parameter marked show: true is kept with its value (after --set) and doc for cosim validate;
// one without it, or with show: false, is not; a show that is not a yes/no is refused by key.
TEST(Scenario, ParametersMarkedShowAreListedWithValueAndDoc) {
  const std::string text =
      mutate("  u: ${flow_lpm / 60000 / 0.01}\n",
             "  u: ${flow_lpm / 60000 / 0.01}\n"
             "  area: {value: 0.01, show: false}\n"
             "  ratio: {value: \"${u / 0.075}\", show: true, doc: \"u / u_mf\"}\n");
  Scenario sc = parse(text, {"flow_lpm=100"});
  ASSERT_EQ(sc.shown.size(), 1u);
  EXPECT_EQ(sc.shown[0].name, "ratio");
  EXPECT_NEAR(sc.shown[0].value, 100.0 / 60000.0 / 0.01 / 0.075, 1e-12);
  EXPECT_EQ(sc.shown[0].doc, "u / u_mf");
  EXPECT_TRUE(parse(kGood).shown.empty());
  expectError(mutate("  flow_lpm: 50\n", "  flow_lpm: {value: 50, show: often}\n"),
              {"parameters.flow_lpm.show", "true or false"});
}

// kGood with coating: a box zone of two keys (min, max) that a cylinder does not take.
const std::string kZoned = std::string(kGood) +
                           "  mass_transfer: { law: ranz_marshall }\n"
                           "  coating_zone: { shape: box, min: [-1, -1, 0], max: [1, 1, 0.025] }\n";
const char* kCylinder =
    "models.coating_zone={shape: cylinder, base: [0, 0, 0.004], axis: [0, 0, 1], length: 0.03, "
    "radius: 0.01}";

// The keys of the resolved coating zone, sorted.
std::vector<std::string> zoneKeys(const Scenario& sc) {
  std::vector<std::string> keys;
  for (const auto& kv : sc.resolved["models"]["coating_zone"])
    keys.push_back(kv.first.as<std::string>());
  std::sort(keys.begin(), keys.end());
  return keys;
}

TEST(Scenario, SetWithAMapReplacesTheWholeNode) {
  Scenario sc = parse(kZoned, {kCylinder});
  ASSERT_TRUE(sc.models.coating_zone);
  EXPECT_EQ(sc.models.coating_zone->law, "cylinder");
  EXPECT_EQ(zoneKeys(sc), (std::vector<std::string>{"axis", "base", "length", "radius", "shape"}));
  EXPECT_EQ(sc.resolved["models"]["coating_zone"]["radius"].as<double>(), 0.01);
  EXPECT_EQ(sc.resolved["models"]["coating_zone"]["base"][2].as<double>(), 0.004);
  // The zone is built: a point on the axis 1 cm above the base is inside, one beyond the radius
  // is not.
  auto zone = cosim::models::Registry::instance().makeZone(sc.models.coating_zone->law,
                                                           sc.models.coating_zone->params);
  const double in[3] = {0, 0, 0.014}, out[3] = {0.011, 0, 0.014};
  EXPECT_TRUE(zone->contains(in));
  EXPECT_FALSE(zone->contains(out));
  // A list value replaces a list, and the rest of the scene is untouched.
  Scenario sc2 = parse(kZoned, {"models.coating_zone.max=[1, 1, 0.05]"});
  EXPECT_EQ(sc2.resolved["models"]["coating_zone"]["max"][2].as<double>(), 0.05);
  EXPECT_EQ(zoneKeys(sc2), (std::vector<std::string>{"max", "min", "shape"}));
}

TEST(Scenario, UnsetRemovesANodeBeforeTheSetsRebuildIt) {
  Scenario none = parse(kZoned, {}, {"models.coating_zone"});
  EXPECT_FALSE(none.models.coating_zone);  // coat everywhere
  EXPECT_FALSE(none.resolved["models"]["coating_zone"]);
  Scenario sc =
      parse(kZoned,
            {"models.coating_zone.shape=sphere", "models.coating_zone.center=[0, 0, 0.01]",
             "models.coating_zone.radius=0.005"},
            {"models.coating_zone"});
  ASSERT_TRUE(sc.models.coating_zone);
  EXPECT_EQ(sc.models.coating_zone->law, "sphere");
  EXPECT_EQ(zoneKeys(sc), (std::vector<std::string>{"center", "radius", "shape"}));
  // A parameter by its bare name, as for --set.
  EXPECT_FALSE(parse(kGood, {}, {"d"}).parameters.count("d"));
}

TEST(Scenario, PlanLeavesOutWhatTheSceneDoesNotNeed) {
  // No mass transfer: no precursor fields anywhere.
  Scenario sc = parse(kGood);
  auto m = makeModels(sc);
  Plan p = makePlan(sc, m);
  EXPECT_TRUE(p.fluid);
  EXPECT_FALSE(p.coating);
  for (const auto* list :
       {&p.fluid_send, &p.fluid_receive, &p.particles_send, &p.particles_receive}) {
    for (const auto& f : *list) {
      EXPECT_EQ(f.find("precursor"), std::string::npos) << f;
      EXPECT_EQ(f.find("coating"), std::string::npos) << f;
      EXPECT_NE(f, "transfer_coefficient");
    }
  }
  // No models at all: the fluid participant is not started.
  std::string nomodels = kGood;
  nomodels = nomodels.substr(0, nomodels.find("models:"));
  Scenario sc2 = parse(nomodels);
  auto m2 = makeModels(sc2);
  Plan p2 = makePlan(sc2, m2);
  EXPECT_FALSE(p2.fluid);
  ASSERT_FALSE(p2.notes.empty());
  EXPECT_NE(p2.notes.front().find("not started"), std::string::npos);
}

// ---- malformed scenarios: one specific message each
// ----------------------------------------------

TEST(ScenarioErrors, NotYaml) { expectError("name: [unclosed\n", {"not valid YAML"}); }

TEST(ScenarioErrors, UnknownTopLevelKeyIsATypo) {
  expectError(std::string(kGood) + "modles: {}\n", {"modles", "unknown key", "models"});
}

TEST(ScenarioErrors, MissingCouplingSection) {
  expectError(mutate("coupling: { dt: 1.0e-4, dem_steps: 10, end_time: 0.01 }", ""),
              {"coupling", "missing section"});
}

TEST(ScenarioErrors, NegativeTimeStep) {
  expectError(mutate("dt: 1.0e-4", "dt: -1.0e-4"), {"coupling.dt", "must be > 0", "bad.yaml:10:"});
}

TEST(ScenarioErrors, TimeStepNotANumber) {
  expectError(mutate("dt: 1.0e-4", "dt: fast"), {"coupling.dt", "expected a number", "'fast'"});
}

TEST(ScenarioErrors, FractionalDemSteps) {
  expectError(mutate("dem_steps: 10", "dem_steps: 2.5"), {"coupling.dem_steps", "whole number"});
}

TEST(ScenarioErrors, CpusNeitherOffNorAuto) {
  expectError(mutate("dem_steps: 10", "dem_steps: 10, cpus: all"),
              {"coupling.cpus", "expected 'off' or 'auto'", "'all'"});
}

TEST(ScenarioErrors, UnknownAdapter) {
  expectError(mutate("adapter: analytic-fluid", "adapter: ansys"),
              {"participants.fluid.adapter", "unknown adapter 'ansys'", "openfoam"});
}

TEST(ScenarioErrors, AdapterInTheWrongRole) {
  expectError(mutate("adapter: free-particles", "adapter: openfoam"),
              {"participants.particles.adapter", "cannot be the 'particles' participant"});
}

TEST(ScenarioErrors, UnknownDragLaw) {
  expectError(mutate("law: stokes", "law: stoke"),
              {"models.drag", "unknown drag law 'stoke'", "stokes"});
}

TEST(ScenarioErrors, UndisturbedVelocityWithAPrescribedFlow) {
  expectError(mutate("law: stokes", "law: stokes, undisturbed_velocity: self_disturbance"),
              {"models.drag.undisturbed_velocity", "analytic-fluid", "not two-way coupled"});
  expectError(
      mutate("law: stokes", "law: stokes, undisturbed_velocity: self_disturbance_transient"),
      {"models.drag.undisturbed_velocity", "self_disturbance_transient", "not two-way coupled"});
  expectError(mutate("law: stokes", "law: stokes, undisturbed_velocity: selfdisturbance"),
              {"models.drag", "known: none, self_disturbance"});
}

TEST(ScenarioErrors, CoarseGrainingBelowOne) {
  expectError(std::string(kGood) + "constants: { cg: 0.5 }\n", {"constants.cg", ">= 1"});
}

TEST(ScenarioErrors, VoidageBoundOutsideUnitInterval) {
  expectError(std::string(kGood) + "constants: { min_voidage: 1.5 }\n",
              {"constants.min_voidage", "(0, 1)"});
}

TEST(ScenarioErrors, UnknownParameterInExpression) {
  expectError(mutate("${flow_lpm / 60000 / 0.01}", "${flow / 60000}"),
              {"parameters.u", "unknown parameter 'flow'", "flow_lpm"});
}

TEST(ScenarioErrors, DragWithoutFluidParticipant) {
  expectError(
      mutate("  fluid: { adapter: analytic-fluid, options: { velocity: [0, 0, \"${u}\"] } }\n", ""),
      {"participants.fluid", "missing", "drag"});
}

TEST(ScenarioErrors, MissingFilesFolder) {
  expectError(mutate("adapter: free-particles,", "adapter: free-particles, files: no-such-folder,"),
              {"participants.particles.files", "does not exist"});
}

TEST(ScenarioErrors, SetOfUnknownParameter) {
  expectError(kGood, {"--set flowlpm=3", "no parameter 'flowlpm'"}, {"flowlpm=3"});
}

TEST(ScenarioErrors, SetOfOneKeyOfAZoneKeepsTheOldKeysAndNamesTheOverride) {
  // The old box keys stay: the cylinder refuses them, and the message says the shape came from
  // the command line.
  expectError(kZoned,
              {"bad.yaml:", "models.coating_zone", "unknown parameter 'max'",
               "models.coating_zone.shape comes from the command line",
               "--set models.coating_zone.shape=cylinder"},
              {"models.coating_zone.shape=cylinder"});
}

TEST(ScenarioErrors, BadValueInAWholeNodeNamesTheCommandLineAndTheKey) {
  const std::string set =
      "models.coating_zone={shape: cylinder, base: [0, 0, 0.004], axis: [0, 0, 1], length: 0.03, "
      "radius: -0.01}";
  try {
    parse(kZoned, {set});
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    // "command line --set <as given>: <key>: <what>", no line of the file (the value is not in it)
    EXPECT_NE(msg.find("command line --set " + set + ": models.coating_zone: "), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("radius"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("bad.yaml:1"), std::string::npos) << msg;
  }
  expectError(
      kZoned,
      {"--set models.coating_zone={shape: cylinder, radius: 0.01}", "models.coating_zone", "base"},
      {"models.coating_zone={shape: cylinder, radius: 0.01}"});
  expectError(kZoned, {"--set models.coating_zone={shape: cylinder", "not valid YAML"},
              {"models.coating_zone={shape: cylinder"});
  expectError(kGood, {"--set coupling={dt: 1.0e-4}", "coupling.end_time", "missing"},
              {"coupling={dt: 1.0e-4}"});
}

TEST(ScenarioErrors, UnsetOfAMissingOrRequiredKey) {
  expectError(kZoned, {"--unset models.coating_zon", "no 'models.coating_zon'"}, {},
              {"models.coating_zon"});
  expectError(kZoned, {"--unset nosuch", "no 'parameters.nosuch'"}, {}, {"nosuch"});
  expectError(kZoned, {"--unset models.drag.law.x", "no 'models.drag.law' section"}, {},
              {"models.drag.law.x"});
  expectError(kGood, {"--unset coupling.dt", "coupling.dt", "missing"}, {}, {"coupling.dt"});
  expectError(kGood, {"command line --unset coupling: coupling: missing section"}, {},
              {"coupling"});
}

TEST(ScenarioErrors, EndTimeBeforeStart) {
  expectError(mutate("end_time: 0.01", "end_time: 0.01, start_time: 0.02"),
              {"coupling.end_time", "later than start_time"});
}

TEST(ScenarioErrors, CoatingZoneWithoutMassTransfer) {
  expectError(
      std::string(kGood) + "  coating_zone: { shape: sphere, centre: [0, 0, 0], radius: 0.01 }\n",
      {"models.coating_zone", "mass_transfer"});
}

TEST(ScenarioErrors, BadMpiRankCount) {
  expectError(mutate("adapter: free-particles,", "adapter: free-particles, mpi: 0,"),
              {"participants.particles.mpi", ">= 1"});
}

TEST(ScenarioErrors, MissingFileIsNamed) {
  try {
    loadScenario("/nonexistent/scenario.yaml");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.yaml"), std::string::npos);
  }
}

// ---- expressions
// ----------------------------------------------------------------------------------

TEST(Expression, ArithmeticAndFunctions) {
  Variables v{{"a", 2.0}, {"flow_lpm", 50.0}};
  EXPECT_DOUBLE_EQ(evaluate("1 + 2 * 3", v), 7.0);
  EXPECT_DOUBLE_EQ(evaluate("(1 + 2) * 3", v), 9.0);
  EXPECT_DOUBLE_EQ(evaluate("2 ^ 3 ^ 2", v), 512.0);
  EXPECT_DOUBLE_EQ(evaluate("-a^2", v), -4.0);
  EXPECT_DOUBLE_EQ(evaluate("sqrt(16) + max(a, 3)", v), 7.0);
  EXPECT_NEAR(evaluate("flow_lpm / 60000 / (pi * 0.05^2)", v), 50.0 / 60000.0 / (M_PI * 0.0025),
              1e-15);
  EXPECT_THROW(evaluate("1 / 0", v), ExpressionError);
  EXPECT_THROW(evaluate("2 +", v), ExpressionError);
}

TEST(Expression, SubstituteKeepsTextAndFormatsExactly) {
  Variables v{{"u", 0.1}, {"n", 3}};
  EXPECT_EQ(substitute("internalField uniform (0 0 ${u});", v), "internalField uniform (0 0 0.1);");
  EXPECT_EQ(substitute("run ${n*1000}", v), "run 3000");
  const double x = 1.0 / 3.0;
  EXPECT_EQ(std::stod(formatNumber(x)), x);
  EXPECT_THROW(substitute("${u", v), ExpressionError);
}

TEST(Expression, DoubleDollarIsALiteral) {
  Variables v{{"u", 0.1}};
  // LIGGGHTS and shell variables survive templating when written $${...}
  EXPECT_EQ(substitute("variable vz equal $${vel} + ${u}", v), "variable vz equal ${vel} + 0.1");
  EXPECT_EQ(substitute("$${a}$${b}", v), "${a}${b}");
}

// ---- the keys each section declares are the documented ones
// ----------------------------------------------------------

// The reference page is what `cosim reference` prints from the declarations: a key added,
// removed or redocumented in the code without the page (or the page edited by hand) fails here.
TEST(ScenarioDocs, ReferencePageIsMadeFromTheDeclarations) {
  std::ifstream in(std::string(COSIM_SOURCE_DIR) + "/docs/scenario-reference.md");
  ASSERT_TRUE(in);
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(page == scenarioReference())
      << "docs/scenario-reference.md differs from the declarations: run "
         "`build/bin/cosim reference > docs/scenario-reference.md`";
}

// Each adapter's option table in its page is what the adapter prints from its declarations
// (--options-reference), between the page's markers.
TEST(ScenarioDocs, AdapterOptionTablesAreMadeFromTheAdapters) {
  const std::vector<std::pair<std::string, std::string>> adapters = {
      {"cosim-analytic-fluid", "docs/analytic-adapters.md"},
      {"cosim-free-particles", "docs/analytic-adapters.md"},
      {"cosim-liggghts", "docs/liggghts.md"},
      {"cosimFoam", "docs/openfoam.md"}};
  for (const auto& [exe, page_name] : adapters) {
    const std::filesystem::path bin = std::filesystem::path(COSIM_BIN_DIR) / exe;
    if (!std::filesystem::exists(bin)) {
      std::cout << "[ note ] " << exe << " is not built here; its table is not compared\n";
      continue;
    }
    std::string printed;
    {
      FILE* p = popen(("'" + bin.string() + "' --options-reference").c_str(), "r");
      ASSERT_NE(p, nullptr) << exe;
      char buf[4096];
      for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) printed.append(buf, n);
      EXPECT_EQ(pclose(p), 0) << exe;
    }
    EXPECT_EQ(printed.rfind("| option | default | meaning |\n", 0), 0u) << exe << ": " << printed;
    std::ifstream in(std::string(COSIM_SOURCE_DIR) + "/" + page_name);
    ASSERT_TRUE(in) << page_name;
    const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string begin = "<!-- the options of " + exe + ":";
    const std::string end = "<!-- end of the options of " + exe + " -->";
    const auto b = page.find(begin);
    ASSERT_NE(b, std::string::npos) << page_name << " has no table of " << exe;
    const auto from = page.find('\n', b) + 1;
    const auto to = page.find(end, from);
    ASSERT_NE(to, std::string::npos) << page_name << ": the table of " << exe << " has no end";
    EXPECT_EQ(page.substr(from, to - from), printed)
        << page_name << ": the table of " << exe << " differs from `" << exe
        << " --options-reference`; paste its output between the markers";
  }
}

TEST(ScenarioDocs, EveryDeclaredKeyHasItsMeaningAndIsInTheReference) {
  const std::string page = scenarioReference();
  const std::vector<std::pair<std::string, const std::vector<KeySpec>*>> sections = {
      {"", &topLevelKeys()},
      {"parameters.NAME.", &parameterKeys()},
      {"coupling.", &CouplingSection::keys()},
      {"constants.", &ConstantsSection::keys()},
      {"participants.NAME.", &ParticipantSpec::keys()},
      {"participants.NAME.slurm.", &SlurmLaunch::keys()},
      {"models.", &ModelsSection::keys()},
      {"models.drag.", &ModelsSection::dragKeys()},
      {"output.", &OutputSection::keys()},
      {"transport.", &TransportSection::keys()},
      {"checks.", &ChecksSection::keys()},
      {"observables.NAME.", &observableKeys()},
      {"checkpoint.", &CheckpointSection::keys()}};
  for (const auto& [prefix, keys] : sections) {
    EXPECT_FALSE(keys->empty()) << prefix;
    for (const auto& k : *keys) {
      EXPECT_FALSE(k.doc.empty()) << prefix << k.name;
      EXPECT_FALSE(k.default_value.empty()) << prefix << k.name;
      EXPECT_NE(page.find("| `" + prefix + k.name + "` | "), std::string::npos)
          << prefix << k.name << " is not a row of the reference";
    }
  }
  // A '|' in a meaning is escaped, so that every row has its three cells
  std::istringstream rows(page);
  for (std::string row; std::getline(rows, row);) {
    if (row.rfind("| `", 0) != 0) continue;
    int cells = 0;
    for (std::size_t i = 0; i < row.size(); ++i)
      if (row[i] == '|' && (i == 0 || row[i - 1] != '\\')) ++cells;
    EXPECT_TRUE(cells == 4 || cells == 3) << row;  // key | default | meaning, or key | names
  }
}

// A bad --set value is blamed on the command line, never on a line of a file it is not in.
TEST(ScenarioErrors, BadSetValueIsBlamedOnTheCommandLine) {
  try {
    parse(kGood, {"coupling.dt=abc"});
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("command line --set coupling.dt=abc: coupling.dt: expected a number, "
                        "got 'abc'",
                        0),
              0u)
        << msg;
    EXPECT_NE(msg.find("(scene "), std::string::npos) << "which scene it was for: " << msg;
    EXPECT_EQ(msg.find("bad.yaml:"), std::string::npos) << msg;
  }
  // One parameter of a model: the model checks its parameters together under models.drag, the
  // value is the command line's.
  const std::string zoned = std::string(kGood) +
                            "  mass_transfer: { law: ranz_marshall }\n"
                            "  coating_zone: { shape: sphere, center: [0, 0, 0], radius: 0.01 }\n";
  try {
    parse(zoned, {"models.coating_zone.radius=-1"});
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(
        msg.rfind("command line --set models.coating_zone.radius=-1: models.coating_zone: ", 0), 0u)
        << msg;
    EXPECT_NE(msg.find("'radius'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("bad.yaml:"), std::string::npos) << msg;
  }
  try {
    parse(kGood, {"models.drag.law=stoke"});
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "command line --set models.drag.law=stoke: models.drag.law: unknown drag law "
                  "'stoke'",
                  0),
              0u)
        << e.what();
  }
  // A value of the file checked against one of the command line: the file's line, and the
  // command line's change beside it.
  try {
    parse(kGood, {"coupling.end_time=1e-9"});
    ADD_FAILURE() << "accepted";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.yaml:10: coupling.dt: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("(the command line changed the scene: --set coupling.end_time=1e-9)"),
              std::string::npos)
        << msg;
  }
}

// A scene that extends another: each message names the file and line that gave the key.
TEST(ScenarioErrors, ExtendedSceneErrorsNameTheFileThatGaveTheKey) {
  const fs::path dir = fs::temp_directory_path() / ("cosim-extends-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "base.yaml") << kGood;  // coupling at line 10
  std::ofstream(dir / "small.yaml") << "extends: base.yaml\n"
                                       "name: small\n"
                                       "coupling:\n"
                                       "  end_time: 0.02\n";
  const fs::path small = dir / "small.yaml", base = dir / "base.yaml";
  auto error = [&](const std::vector<std::string>& sets) {
    try {
      loadScenario(small, sets);
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "accepted";
    return std::string();
  };
  EXPECT_DOUBLE_EQ(loadScenario(small).coupling.end_time, 0.02);
  // models.drag.law is base.yaml's (line 12), whatever the command line changed elsewhere.
  std::string msg = error({"models.drag={law: stokes, k: 1}"});
  EXPECT_EQ(msg.rfind("command line --set models.drag={law: stokes, k: 1}: models.drag:", 0), 0u)
      << msg;
  msg = error({"coupling.dt=abc"});
  EXPECT_EQ(msg.rfind("command line --set coupling.dt=abc: coupling.dt: expected a number", 0), 0u)
      << msg;
  msg = error({"coupling.end_time=1e-9"});
  EXPECT_EQ(msg.rfind(base.string() + ":10: coupling.dt: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("--set coupling.end_time=1e-9"), std::string::npos) << msg;
  // A key of the extending file: its own line.
  std::ofstream(small, std::ios::app) << "  dem_steps: 2.5\n";
  msg = error({});
  EXPECT_EQ(msg.rfind(small.string() + ":5: coupling.dem_steps: ", 0), 0u) << msg;
  fs::remove_all(dir);
}

// kGood with its flow given with a range: 0 to 300 L/min, the cap
// from an earlier parameter (3e6 d), so that the range can follow the scene's other choices.
std::string rangedScene(const std::string& flow = "50", const std::string& dcap = "${3e6 * d}") {
  std::string s = kGood;
  const std::string from = "  flow_lpm: 50\n";
  s.replace(s.find(from), from.size(),
            "  flow_lpm: {value: " + flow + ", min: 0, max: \"" + dcap +
                "\", doc: \"fluidization flow [L/min]\"}\n");
  return s;
}

TEST(Scenario, AParameterWithARangeGivesItsValueAndTheResolvedSceneHoldsTheBareNumber) {
  Scenario sc = parse(rangedScene());
  EXPECT_DOUBLE_EQ(sc.parameters.at("flow_lpm"), 50.0);
  EXPECT_NEAR(sc.parameters.at("u"), 50.0 / 60000.0 / 0.01, 1e-15);
  ASSERT_TRUE(sc.resolved["parameters"]["flow_lpm"].IsScalar());
  EXPECT_EQ(sc.resolved["parameters"]["flow_lpm"].Scalar(), "50");
  // --set of a bare number changes the value and keeps the range; the bounds are inclusive.
  sc = parse(rangedScene(), {"flow_lpm=0"});
  EXPECT_DOUBLE_EQ(sc.parameters.at("flow_lpm"), 0.0);
  sc = parse(rangedScene(), {"flow_lpm=1"});
  EXPECT_NEAR(sc.parameters.at("u"), 1.0 / 60000.0 / 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(parse(rangedScene(), {"flow_lpm=1.0"}).parameters.at("flow_lpm"), 1.0);
  // The cap is 3e6 d = 300 L/min at d = 1e-4: 300 is in, and the cap follows d.
  EXPECT_DOUBLE_EQ(parse(rangedScene("300"), {}).parameters.at("flow_lpm"), 300.0);
  EXPECT_DOUBLE_EQ(parse(rangedScene("600"), {"d=2e-4"}).parameters.at("flow_lpm"), 600.0);
}

TEST(ScenarioErrors, AParameterOutsideItsRangeIsRefusedWithTheRangeAndWhereItCameFrom) {
  // From the command line: the override is blamed, with the range and what the parameter is.
  try {
    parse(rangedScene(), {"flow_lpm=-5"});
    ADD_FAILURE() << "accepted flow_lpm=-5";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(
        msg.rfind("command line --set flow_lpm=-5: parameters.flow_lpm: -5 is outside [0, 300]", 0),
        0u)
        << msg;
    EXPECT_NE(msg.find("fluidization flow [L/min]"), std::string::npos) << msg;
  }
  // Just above the cap (300 L/min at d = 1e-4) is refused, as is 200 when d halves the cap.
  expectError(rangedScene("300.0001"), {"bad.yaml:5:", "parameters.flow_lpm", "outside [0, 300]"});
  expectError(rangedScene("200"), {"parameters.flow_lpm", "outside [0, 150]", "--set d=5e-5"},
              {"d=5e-5"});
  // The range's own mistakes.
  expectError(rangedScene("1", "-1"),
              {"parameters.flow_lpm.min", "range is empty", "min 0 > max -1"});
  expectError(rangedScene("1", "${q}"), {"parameters.flow_lpm.max", "unknown parameter 'q'"});
  expectError(rangedScene("abc"), {"parameters.flow_lpm.value", "expected a number, got 'abc'"});
  expectError(mutate("  flow_lpm: 50\n", "  flow_lpm: {min: 0}\n"),
              {"parameters.flow_lpm.value", "missing"});
  expectError(mutate("  flow_lpm: 50\n", "  flow_lpm: {value: 50, minimum: 0}\n"),
              {"parameters.flow_lpm.minimum", "unknown key", "value, min, max, doc"});
}

TEST(Scenario, AnExtendingSceneChangesTheValueOfARangedParameterAndKeepsItsRange) {
  const fs::path dir = fs::temp_directory_path() / ("cosim-ranges-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "base.yaml") << rangedScene();
  std::ofstream(dir / "small.yaml") << "extends: base.yaml\nparameters:\n  flow_lpm: 0.5\n";
  std::ofstream(dir / "big.yaml") << "extends: base.yaml\nparameters:\n  flow_lpm: 400\n";
  const Scenario small = loadScenario(dir / "small.yaml");
  EXPECT_DOUBLE_EQ(small.parameters.at("flow_lpm"), 0.5);
  EXPECT_EQ(small.resolved["parameters"]["flow_lpm"].Scalar(), "0.5");
  try {
    loadScenario(dir / "big.yaml");
    ADD_FAILURE() << "accepted flow_lpm 400 above the base's cap of 300";
  } catch (const ScenarioError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(
        msg.rfind((dir / "big.yaml").string() + ":3: parameters.flow_lpm: 400 is outside [0, 300]",
                  0),
        0u)
        << msg;
  }
  fs::remove_all(dir);
}

// The coating bed states the ranges its mesh and models hold for: a careless --set is refused
// before anything starts, in every size of the scene (the sizes extend it).
TEST(ScenarioErrors, TheCoatingBedRefusesValuesOutsideItsRanges) {
  const fs::path bed = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "plasma-coating-bed";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"flow_lpm=-5", "outside [0, inf]"},
      {"cg=0.5", "outside [1, 13.3333]"},  // a parcel is at least one real grain
      {"cg=14", "outside [1, 13.3333]"},   // and at most one 4 mm cell across (300 um grains)
      {"n=0.1", "outside [0.004, "},       // wider than the vessel less a cell on each side
      {"Y_nozzle=1.5", "outside [0, 1]"},
      {"n_grains=0", "outside [1, "},
      {"n_grains=1e6", "outside [1, "},  // more than 0.6 of the vessel above the nozzle holds
      {"insert_seed=7", "outside [10001, inf]"}};
  for (const char* size : {"scenario.yaml", "ci.yaml", "study.yaml"}) {
    EXPECT_NO_THROW(loadScenario(bed / size)) << size;
    for (const auto& [set, range] : cases) {
      try {
        loadScenario(bed / size, {set});
        ADD_FAILURE() << size << " accepted --set " << set;
      } catch (const ScenarioError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind("command line --set " + set + ": parameters.", 0), 0u) << msg;
        EXPECT_NE(msg.find(range), std::string::npos) << msg;
      }
    }
  }
}

// The paper's round reactor likewise, at its size and in CI's miniature: a mass in grams, a
// nozzle wider than the O-grid's square around it, no protrusion, a vessel of a few cells.
TEST(ScenarioErrors, TheRoundReactorRefusesValuesOutsideItsRanges) {
  const fs::path dir = fs::path(COSIM_SOURCE_DIR) / "scenarios" / "plasma-coating-reactor";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bed_mass=200", "parameters.bed_mass"},  // grams for kg: far more than the vessel holds
      {"d_nozzle=0.05", "parameters.d_nozzle"},
      {"hn=0", "parameters.hn"},
      {"R=0.01", "parameters.R"},
      {"cell=0.01", "parameters.cell"},
      {"nozzle_cells=6", "parameters.nozzle_cells"}};
  for (const char* size : {"scenario.yaml", "tiny.yaml"}) {
    EXPECT_NO_THROW(loadScenario(dir / size)) << size;
    for (const auto& [set, key] : cases) {
      try {
        loadScenario(dir / size, {set});
        ADD_FAILURE() << size << " accepted --set " << set;
      } catch (const ScenarioError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind("command line --set " + set + ": " + key, 0), 0u) << msg;
        EXPECT_NE(msg.find("is outside ["), std::string::npos) << msg;
      }
    }
  }
}
