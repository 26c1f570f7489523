// Every scenario name is registered, and every declared field is a real wire field name.
#include "cosim/models/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cosim/link/fields.h"

namespace cosim::models {
namespace {

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

const std::vector<std::string> kSampleFields = {
    field::position,        field::velocity,          field::radius,
    field::fluid_velocity,  field::voidage,           field::fluid_density,
    field::fluid_viscosity, field::pressure_gradient, field::precursor_fraction,
    field::cell_size};

void expectValidFields(const Model& m) {
  for (const auto& f : m.requiredFields()) {
    EXPECT_TRUE(contains(kSampleFields, f)) << m.name() << " declares '" << f << "'";
  }
}

TEST(Registry, EveryScenarioNameIsRegistered) {
  auto& r = Registry::instance();
  for (const auto& n :
       {"stokes", "schiller_naumann", "di_felice", "gidaspow", "koch_hill", "beetstra"}) {
    EXPECT_TRUE(contains(r.dragNames(), n)) << n;
    auto law = r.makeDrag(n, Parameters(n));
    EXPECT_EQ(law->name(), n);
    expectValidFields(*law);
  }
  EXPECT_TRUE(contains(r.forceNames(), "pressure_gradient"));
  expectValidFields(*r.makeForce("pressure_gradient", Parameters("f")));
  for (const auto& n : {"deen_gunn", "gunn", "ranz_marshall"}) {
    EXPECT_TRUE(contains(r.massTransferNames(), n)) << n;
    auto law = r.makeMassTransfer(n, Parameters(n));
    EXPECT_EQ(law->name(), n);
    expectValidFields(*law);
    EXPECT_FALSE(contains(law->requiredFields(), "cell_size"));
  }
  for (const auto& n : {"cylinder", "cone_frustum", "box", "sphere", "union"}) {
    EXPECT_TRUE(contains(r.zoneNames(), n)) << n;
  }
}

TEST(Registry, BeetstraAsksForCellSizeOnlyWhenFiltered) {
  auto& r = Registry::instance();
  auto plain = r.makeDrag("beetstra", Parameters("beetstra"));
  EXPECT_FALSE(contains(plain->requiredFields(), "cell_size"));
  Parameters p("beetstra");
  p.set("filtered", 1.0);  // numbers 1/0 are accepted as well as true/false
  p.set("particle_density", 1750.0);
  auto filtered = r.makeDrag("beetstra", p);
  EXPECT_TRUE(contains(filtered->requiredFields(), "cell_size"));
  expectValidFields(*filtered);
}

TEST(Registry, DragLawsNeedTheFieldsOfTheirFormula) {
  auto& r = Registry::instance();
  for (const auto& n : {"schiller_naumann", "di_felice", "gidaspow", "koch_hill", "beetstra"}) {
    const auto f = r.makeDrag(n, Parameters(n))->requiredFields();
    for (const auto& need :
         {"radius", "velocity", "fluid_velocity", "voidage", "fluid_density", "fluid_viscosity"}) {
      EXPECT_TRUE(contains(f, need)) << n << " lacks " << need;
    }
  }
  const auto s = r.makeDrag("stokes", Parameters("stokes"))->requiredFields();
  EXPECT_FALSE(contains(s, "voidage"));
  EXPECT_TRUE(contains(s, "fluid_viscosity"));
}

}  // namespace
}  // namespace cosim::models

namespace cosim::models {
namespace {

TEST(Parameters, FlagAcceptsWordsAndNumbers) {
  Parameters p("m");
  p.setText("a", "Yes");
  p.setText("b", "off");
  p.set("c", 1.0);
  p.set("d", 0.0);
  p.set("e", 2.0);
  EXPECT_TRUE(p.flag("a", false));
  EXPECT_FALSE(p.flag("b", true));
  EXPECT_TRUE(p.flag("c", false));
  EXPECT_FALSE(p.flag("d", true));
  EXPECT_TRUE(p.flag("missing", true));
  EXPECT_THROW(p.flag("e", false), ModelError);
}

TEST(Parameters, WithoutDropsOneKeyAndRenames) {
  Parameters p("old");
  p.setText("shape", "sphere");
  p.set("radius", 1.0);
  const Parameters q = p.without("shape", "new");
  EXPECT_FALSE(q.has("shape"));
  EXPECT_EQ(q.number("radius"), 1.0);
  EXPECT_EQ(q.owner(), "new");
  EXPECT_TRUE(p.has("shape"));
}

}  // namespace
}  // namespace cosim::models
