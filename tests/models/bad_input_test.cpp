// Bad input: clear errors naming the model and the parameter/field; no NaN or Inf ever leaves a
// model over a grid of extreme (valid) inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "cosim/models/input_checks.h"
#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

// Runs f and returns the ModelError message ("" if nothing was thrown).
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

void expectError(const std::function<void()>& f, std::initializer_list<const char*> parts) {
  const std::string msg = errorOf(f);
  ASSERT_FALSE(msg.empty()) << "no ModelError thrown";
  for (const char* part : parts) EXPECT_NE(msg.find(part), std::string::npos) << msg;
}

TEST(BadInput, UnknownNamesListTheKnownOnes) {
  auto& r = Registry::instance();
  expectError([&] { r.makeDrag("beetstraa", Parameters("drag")); },
              {"unknown drag law 'beetstraa'", "beetstra", "koch_hill", "stokes"});
  expectError([&] { r.makeMassTransfer("gun", Parameters("mt")); },
              {"unknown mass transfer law 'gun'", "deen_gunn", "ranz_marshall"});
  expectError([&] { r.makeZone("cube", Parameters("z")); }, {"'cube'", "box", "cone_frustum"});
  expectError([&] { r.makeForce("lift", Parameters("f")); }, {"'lift'", "pressure_gradient"});
}

TEST(BadInput, ParameterErrorsNameModelAndKey) {
  auto& r = Registry::instance();
  Parameters typo("models.drag (beetstra)");
  typo.setText("filterd", "true");
  expectError([&] { r.makeDrag("beetstra", typo); },
              {"models.drag (beetstra)", "unknown parameter 'filterd'", "filtered"});
  Parameters nodens("models.drag (beetstra)");
  nodens.setText("filtered", "yes");
  expectError([&] { r.makeDrag("beetstra", nodens); }, {"models.drag", "'particle_density'"});
  Parameters negdens("models.drag (beetstra)");
  negdens.setText("filtered", "on");
  negdens.set("particle_density", -5.0);
  expectError([&] { r.makeDrag("beetstra", negdens); }, {"'particle_density'", "must be > 0"});
  Parameters flag("models.drag (beetstra)");
  flag.setText("filtered", "maybe");
  expectError([&] { r.makeDrag("beetstra", flag); }, {"'filtered'", "true or false"});
  Parameters unused("models.drag (beetstra)");
  unused.set("particle_density", 1750.0);
  expectError([&] { r.makeDrag("beetstra", unused); }, {"'particle_density'", "filtered: true"});
  Parameters half("models.drag (beetstra)");
  half.setText("filtered", "true");
  half.set("particle_density", 1750.0);
  half.set("reference_fluid_density", 1.12);
  expectError([&] { r.makeDrag("beetstra", half); },
              {"'reference_fluid_density'", "'reference_fluid_viscosity'", "neither"});
  half.set("reference_fluid_viscosity", 1.8e-5);
  half.set("reference_fluid_density", 2000.0);
  expectError([&] { r.makeDrag("beetstra", half); }, {"must exceed"});
  Parameters reff("models.drag (beetstra)");
  reff.set("reference_fluid_viscosity", 1.8e-5);
  expectError([&] { r.makeDrag("beetstra", reff); },
              {"'reference_fluid_viscosity'", "filtered: true"});
  Parameters sw("models.drag (gidaspow)");
  sw.set("switch_voidage", 1.5);
  expectError([&] { r.makeDrag("gidaspow", sw); }, {"'switch_voidage'", "out of range"});
  Parameters cd("models.drag (di_felice)");
  cd.setText("drag_coefficient", "newton");
  expectError([&] { r.makeDrag("di_felice", cd); }, {"'drag_coefficient'", "dallavalle"});
  Parameters extra("models.mass_transfer");
  extra.set("sc", 1.0);
  expectError([&] { r.makeMassTransfer("deen_gunn", extra); }, {"unknown parameter 'sc'"});
}

TEST(BadInput, ZoneParameterErrors) {
  auto& r = Registry::instance();
  Parameters cyl("models.coating_zone");
  cyl.setList("base", {0, 0, 0});
  cyl.setList("axis", {0, 0, 0});
  cyl.set("radius", 0.1);
  cyl.set("length", 0.1);
  expectError([&] { r.makeZone("cylinder", cyl); }, {"models.coating_zone", "'axis'", "zero"});
  cyl.setList("axis", {0, 0, 1});
  cyl.set("radius", -0.1);
  expectError([&] { r.makeZone("cylinder", cyl); }, {"'radius'", "must be > 0"});
  Parameters nobase("models.coating_zone");
  nobase.setList("center", {0, 0});
  nobase.set("radius", 1.0);
  expectError([&] { r.makeZone("sphere", nobase); }, {"'center'", "3 numbers"});
  Parameters box("models.coating_zone");
  box.setList("min", {0, 0, 1});
  box.setList("max", {1, 1, 1});
  expectError([&] { r.makeZone("box", box); }, {"'min'", "'max'", "component 2"});
  Parameters cone("models.coating_zone");
  cone.setList("base", {0, 0, 0});
  cone.setList("axis", {0, 0, 1});
  cone.set("length", 1.0);
  cone.set("base_radius", 0.0);
  cone.set("top_radius", 0.0);
  expectError([&] { r.makeZone("cone_frustum", cone); }, {"base_radius", "top_radius"});
  Parameters part("part");
  part.setText("shape", "cube");
  Parameters u("models.coating_zone");
  u.setChild("parts", {part});
  expectError([&] { r.makeZone("union", u); }, {"models.coating_zone part 1", "'cube'"});
  Parameters noshape("part");
  noshape.set("radius", 1.0);
  u.setChild("parts", {noshape});
  expectError([&] { r.makeZone("union", u); }, {"part 1", "'shape'"});
  u.setChild("parts", {});
  expectError([&] { r.makeZone("union", u); }, {"'parts'", "empty"});
  Parameters badpart("part");
  badpart.setText("shape", "sphere");
  badpart.setList("center", {0, 0, 0});
  badpart.set("radius", 0.0);
  u.setChild("parts", {badpart});
  expectError([&] { r.makeZone("union", u); }, {"part 1 (sphere)", "'radius'"});
}

const std::vector<std::string> kDragLaws = {"stokes",   "schiller_naumann", "di_felice",
                                            "gidaspow", "koch_hill",        "beetstra"};
const std::vector<std::string> kMassLaws = {"deen_gunn", "gunn", "ranz_marshall"};

// Evaluates every drag and mass-transfer law on b with constants c.
void evaluateAll(const Batch& b, const SceneConstants& c) {
  std::vector<double> out(b.size());
  for (const auto& n : kDragLaws) {
    Registry::instance().makeDrag(n, Parameters(n))->coefficients(b.view(), c, out.data());
  }
  for (const auto& n : kMassLaws) {
    Registry::instance()
        .makeMassTransfer(n, Parameters(n))
        ->transferCoefficients(b.view(), c, out.data());
  }
}

TEST(BadInput, EvaluationErrorsNameModelFieldAndParcel) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* field;
    std::function<void(Batch&)> spoil;
  };
  const std::vector<Case> cases = {
      {"radius", [](Batch& b) { b.radius[1] = -1e-4; }},
      {"radius", [](Batch& b) { b.radius[1] = 0.0; }},
      {"voidage", [](Batch& b) { b.voidage[1] = 0.0; }},
      {"voidage", [](Batch& b) { b.voidage[1] = 1.5; }},
      {"voidage", [&](Batch& b) { b.voidage[1] = nan; }},
      {"fluid_viscosity", [](Batch& b) { b.fluid_viscosity[1] = 0.0; }},
      {"fluid_density", [](Batch& b) { b.fluid_density[1] = -1.0; }},
      {"fluid_velocity", [&](Batch& b) { b.fluid_velocity[4] = nan; }},
      {"velocity", [](Batch& b) { b.velocity[3] = std::numeric_limits<double>::infinity(); }},
  };
  for (const auto& c : cases) {
    for (const auto& n : kDragLaws) {
      if (n == "stokes" &&
          (std::string(c.field) == "voidage" || std::string(c.field) == "fluid_density")) {
        continue;  // Stokes reads neither
      }
      Batch b;
      b.add(0.5, 1.0, kD, 5.0);
      b.add(0.5, 1.0, kD, 5.0);
      c.spoil(b);
      std::vector<double> K(2);
      auto law = Registry::instance().makeDrag(n, Parameters(n));
      expectError([&] { law->coefficients(b.view(), constants(5.0), K.data()); },
                  {("drag law '" + n + "'").c_str(), c.field, "parcel 1"});
    }
  }
  // A voidage a hair above 1 (round-off in the fluid adapter) is accepted and clamped to 1.
  Batch ok;
  ok.add(1.0 + 1e-12, 0.1, kD, 5.0);
  EXPECT_NO_THROW(evaluateAll(ok, constants(5.0)));
}

// A parcel in no fluid cell arrives with zero samples (contract: lost_ids). With the lost flag set
// every law gives it 0 and does not reject its zero voidage/viscosity; the others are untouched.
TEST(BadInput, LostParcelsGetZeroAndAreNotChecked) {
  Batch b;
  b.add(0.5, 1.0, kD, 5.0);
  b.add(0.5, 1.0, kD, 5.0);
  b.voidage[1] = b.fluid_density[1] = b.fluid_viscosity[1] = 0.0;
  b.fluid_velocity[3] = b.fluid_velocity[4] = b.fluid_velocity[5] = 0.0;
  b.pressure_gradient = {0.0, 0.0, -100.0, 0.0, 0.0, 0.0};
  const std::vector<char> lost = {0, 1};
  ParcelBatch v = b.view();
  v.lost = lost.data();
  Parameters filt("beetstra");
  filt.setText("filtered", "true");
  filt.set("particle_density", kRhoP);
  std::vector<std::unique_ptr<DragLaw>> drag;
  for (const auto& n : kDragLaws) drag.push_back(Registry::instance().makeDrag(n, Parameters(n)));
  drag.push_back(Registry::instance().makeDrag("beetstra", filt));
  for (const auto& law : drag) {
    std::vector<double> K(2, -1.0), Kref(1, -1.0);
    ASSERT_NO_THROW(law->coefficients(v, constants(5.0), K.data())) << law->name();
    Batch one;
    one.add(0.5, 1.0, kD, 5.0);
    law->coefficients(one.view(), constants(5.0), Kref.data());
    EXPECT_EQ(K[0], Kref[0]) << law->name();
    EXPECT_EQ(K[1], 0.0) << law->name();
  }
  for (const auto& n : kMassLaws) {
    std::vector<double> k(2, -1.0);
    ASSERT_NO_THROW(Registry::instance()
                        .makeMassTransfer(n, Parameters(n))
                        ->transferCoefficients(v, constants(5.0), k.data()));
    EXPECT_GT(k[0], 0.0);
    EXPECT_EQ(k[1], 0.0);
  }
  std::vector<double> F(6, 0.0);
  Registry::instance()
      .makeForce("pressure_gradient", Parameters("pg"))
      ->addForces(v, constants(5.0), F.data());
  EXPECT_GT(F[2], 0.0);
  EXPECT_EQ(F[5], 0.0);
  // without the flag the same zero samples are an error naming the parcel
  expectError([&] { drag[1]->coefficients(b.view(), constants(5.0), F.data()); },
              {"parcel 1", "'voidage'"});
}

// A batch remembers the arrays its laws have found valid (a second law does not scan them
// again), but a copy pointing a field at another array, or with other lost parcels, has that
// array scanned: a bad value is never let through by the memo.
TEST(BadInput, AFieldCheckedOnceIsCheckedAgainWhenItsArrayChanges) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Batch b;
  b.add(0.5, 1.0, kD, 5.0);
  b.add(0.5, 1.0, kD, 5.0);
  const ParcelBatch v = b.view();
  const std::vector<std::string> fields = {"fluid_velocity", "voidage"};
  ASSERT_NO_THROW(checkInputs("first law", fields, v, constants(5.0)));
  ASSERT_NO_THROW(checkInputs("second law", fields, v, constants(5.0)));
  // another array for one field (as the undisturbed gas velocity is): scanned, and refused
  std::vector<double> bad_velocity = b.fluid_velocity;
  bad_velocity[4] = nan;
  ParcelBatch q = v;
  q.fluid_velocity = bad_velocity.data();
  expectError([&] { checkInputs("third law", fields, q, constants(5.0)); },
              {"third law", "'fluid_velocity'", "parcel 1"});
  // a parcel marked lost is not checked; the same arrays with that parcel back are
  std::vector<double> bad_voidage = b.voidage;
  bad_voidage[1] = 0.0;
  const std::vector<char> lost = {0, 1};
  ParcelBatch r = v;
  r.voidage = bad_voidage.data();
  r.lost = lost.data();
  ASSERT_NO_THROW(checkInputs("law", fields, r, constants(5.0)));
  r.lost = nullptr;
  expectError([&] { checkInputs("law", fields, r, constants(5.0)); }, {"'voidage'", "parcel 1"});
}

TEST(BadInput, SceneConstantsAreChecked) {
  Batch b;
  b.add(0.5, 1.0, kD, 5.0);
  expectError([&] { evaluateAll(b, constants(0.5)); }, {"'cg'", ">= 1"});
  expectError([&] { evaluateAll(b, constants(5.0, 0.0)); }, {"'min_voidage'", "(0, 1]"});
  expectError([&] { evaluateAll(b, constants(5.0, 1.5)); }, {"'min_voidage'"});
  SceneConstants c = constants(5.0);
  c.schmidt = 0.0;
  expectError([&] { evaluateAll(b, c); }, {"'schmidt'"});
  // zero gravity with the filtered correction
  Parameters p("beetstra");
  p.setText("filtered", "true");
  p.set("particle_density", kRhoP);
  auto law = Registry::instance().makeDrag("beetstra", p);
  SceneConstants g0 = constants(5.0);
  g0.gravity[2] = 0.0;
  double K = 0;
  expectError([&] { law->coefficients(b.view(), g0, &K); }, {"beetstra", "gravity"});
  // particle lighter than the gas
  Batch heavy_gas;
  heavy_gas.add(0.5, 1.0, kD, 5.0, 2000.0);
  expectError([&] { law->coefficients(heavy_gas.view(), constants(5.0), &K); },
              {"particle_density", "fluid density"});
}

TEST(BadInput, MissingFieldIsNamed) {
  Batch b;
  b.add(0.5, 1.0, kD, 5.0);
  ParcelBatch v = b.view();
  v.voidage = nullptr;
  double K = 0;
  auto law = Registry::instance().makeDrag("koch_hill", Parameters("koch_hill"));
  expectError([&] { law->coefficients(v, constants(5.0), &K); }, {"koch_hill", "'voidage'"});
  Parameters p("beetstra");
  p.setText("filtered", "true");
  p.set("particle_density", kRhoP);
  auto filtered = Registry::instance().makeDrag("beetstra", p);
  v = b.view();
  v.cell_size = nullptr;
  expectError([&] { filtered->coefficients(v, constants(5.0), &K); }, {"'cell_size'"});
}

// Every law, every extreme: eps 1e-6..1 (min_voidage 1e-6 so the law really sees it), Re 0..1e5,
// d 1e-7..1 m, mu and rho over decades, cg 1 and 5. Results finite and > 0.
TEST(BadInput, NoNaNOrInfOverAGridOfExtremeInputs) {
  std::vector<std::unique_ptr<DragLaw>> drag;
  for (const auto& n : kDragLaws) drag.push_back(Registry::instance().makeDrag(n, Parameters(n)));
  Parameters dal("di_felice");
  dal.setText("drag_coefficient", "dallavalle");
  drag.push_back(Registry::instance().makeDrag("di_felice", dal));
  Parameters filt("beetstra");
  filt.setText("filtered", "true");
  filt.set("particle_density", 2500.0);
  drag.push_back(Registry::instance().makeDrag("beetstra", filt));
  std::vector<std::unique_ptr<MassTransferLaw>> mass;
  for (const auto& n : kMassLaws) {
    mass.push_back(Registry::instance().makeMassTransfer(n, Parameters(n)));
  }
  const double eps_grid[] = {1e-6, 1e-4,       0.01, 0.1, 0.3,  0.35,     0.4, 0.5,
                             0.6,  0.79999999, 0.8,  0.9, 0.99, 0.999999, 1.0};
  const double re_grid[] = {0.0,  1e-300, 1e-12,   1e-6,   1e-3, 0.1, 1.0,
                            10.0, 100.0,  999.999, 1000.0, 1e4,  1e5};
  const double d_grid[] = {1e-7, 1e-5, 3e-4, 1e-2, 1.0};
  const double fluid[][2] = {{1.12, 1.8e-5}, {1e-3, 1e-7}, {1000.0, 1.0}};  // rho, mu
  std::size_t evaluated = 0;
  for (double cg : {1.0, 5.0}) {
    Batch b;
    for (double eps : eps_grid) {
      for (double Re : re_grid) {
        for (double d : d_grid) {
          for (const auto& f : fluid) {
            const double slip = Re * f[1] / (f[0] * eps * d);
            b.add(eps, slip, d, cg, f[0], f[1], d * 10.0);
          }
        }
      }
    }
    const SceneConstants c = constants(cg, 1e-6);
    std::vector<double> out(b.size());
    for (const auto& law : drag) {
      std::fill(out.begin(), out.end(), std::numeric_limits<double>::quiet_NaN());
      ASSERT_NO_THROW(law->coefficients(b.view(), c, out.data())) << law->name();
      for (std::size_t i = 0; i < out.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out[i]) && out[i] > 0.0)
            << law->name() << " parcel " << i << " K " << out[i];
      }
      evaluated += out.size();
    }
    for (const auto& law : mass) {
      std::fill(out.begin(), out.end(), std::numeric_limits<double>::quiet_NaN());
      ASSERT_NO_THROW(law->transferCoefficients(b.view(), c, out.data())) << law->name();
      for (std::size_t i = 0; i < out.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out[i]) && out[i] > 0.0) << law->name() << " parcel " << i;
      }
      evaluated += out.size();
    }
  }
  EXPECT_EQ(evaluated, 2u * 11u * 15u * 13u * 5u * 3u);
}

}  // namespace
}  // namespace cosim::models::test
