// Loads the example plugin (models/plugins/example_drag, built as a separate shared library) by
// path and evaluates its law.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

TEST(Plugin, ExampleDragLoadsByPathAndEvaluates) {
  auto& r = Registry::instance();
  r.loadPlugin(COSIM_EXAMPLE_PLUGIN);
  auto law = r.makeDrag("tenneti", Parameters("tenneti"));
  EXPECT_EQ(law->name(), "tenneti");
  // Tenneti, Garg & Subramaniam (2011) F with K = 3 pi mu d eps F, cg 5, same points as the
  // built-in drag tests (python3 tests/models/reference_values.py).
  const std::vector<std::pair<double, double>> points = {{1.0, 0.0}, {0.9, 0.05},  {0.6, 0.5},
                                                         {0.4, 2.0}, {0.45, 10.0}, {0.75, 30.0}};
  const std::vector<double> expected = {6.3617251235193305e-06, 1.5411089369990854e-05,
                                        7.9261289373639782e-05, 0.0002713779819642367,
                                        0.00031622669593404278, 0.00017014963799532451};
  Batch b;
  for (auto [eps, w] : points) b.add(eps, w, kD, 5.0);
  std::vector<double> K(b.size());
  law->coefficients(b.view(), constants(5.0), K.data());
  for (std::size_t i = 0; i < K.size(); ++i) EXPECT_TRUE(close(K[i], expected[i], 1e-11)) << i;
  // the plugin uses the shared input checks too
  b.fluid_viscosity[0] = 0.0;
  EXPECT_THROW(law->coefficients(b.view(), constants(5.0), K.data()), ModelError);
}

TEST(Plugin, LoadErrorsNameThePath) {
  auto& r = Registry::instance();
  try {
    r.loadPlugin("/nonexistent/libnothing.so");
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/libnothing.so"), std::string::npos);
  }
  try {
    r.loadPlugin("libm.so.6");  // a real library without cosim_register_models
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("cosim_register_models"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cosim::models::test
