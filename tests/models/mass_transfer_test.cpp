// Mass-transfer laws against independent values, the single-sphere limit and coarse graining.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "cosim/models/mass/deen_gunn.h"
#include "cosim/models/mass/gunn.h"
#include "cosim/models/mass/ranz_marshall.h"
#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

const std::vector<std::pair<double, double>> kPoints = {{1.0, 0.0},  {0.9, 0.05},  {0.6, 0.5},
                                                        {0.4, 2.0},  {0.45, 10.0}, {0.75, 30.0},
                                                        {0.99, 1.0}, {0.9, 100.0}, {0.2, 1.0}};

// k [kg/s per unit mass fraction] = cg^3 K_m rho pi d^2, K_m = Sh D / d, D = mu/(rho Sc), Sc = 1,
// cg = 5, same gas and points as the drag tests; python3 tests/models/reference_values.py.
const std::vector<std::pair<const char*, std::vector<double>>> kReference = {
    {"deen_gunn",
     {4.2411500823462206e-06, 5.4186169672398708e-06, 9.9232516047802975e-06,
      1.8735759461347607e-05, 3.529094456228136e-05, 4.4057729922672755e-05, 8.4753010630235248e-06,
      8.0774197760775877e-05, 1.6114239918151032e-05}},
    {"gunn",
     {4.2411500823462206e-06, 7.5524451715644919e-06, 1.4084239286418961e-05,
      2.5653281103860234e-05, 4.3339786430566379e-05, 4.6211097975765225e-05,
      1.1689305200929184e-05, 7.2293971816206183e-05, 2.2632014431469724e-05}},
    {"ranz_marshall",
     {4.2411500823462206e-06, 5.4072735595074068e-06, 7.2520679534573907e-06,
      9.1579583767791348e-06, 1.590238485395807e-05, 3.0316463733254551e-05, 9.7107540175231409e-06,
      5.6391777384162884e-05, 7.493313080158506e-06}},
};

std::vector<double> evaluate(const std::string& name, const Batch& b, const SceneConstants& c) {
  auto law = Registry::instance().makeMassTransfer(name, Parameters(name));
  std::vector<double> k(b.size(), -1.0);
  law->transferCoefficients(b.view(), c, k.data());
  return k;
}

Batch pointsBatch(double cg) {
  Batch b;
  for (auto [eps, w] : kPoints) b.add(eps, w, kD, cg);
  return b;
}

TEST(MassTransfer, MatchesIndependentReferenceValues) {
  for (const auto& [name, ref] : kReference) {
    const auto k = evaluate(name, pointsBatch(5.0), constants(5.0));
    for (std::size_t i = 0; i < k.size(); ++i) {
      EXPECT_TRUE(close(k[i], ref[i], 1e-11)) << name << " point " << i;
    }
  }
}

// Single sphere in still gas: Sh = 2 for all three laws, so k = cg^3 2 pi mu d / Sc.
TEST(MassTransfer, SingleSphereAtRestHasShTwo) {
  EXPECT_DOUBLE_EQ(deenGunnSherwood(1.0, 0.0, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(gunnSherwood(1.0, 0.0, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(ranzMarshallSherwood(0.0, 1.0), 2.0);
  Batch b;
  b.add(1.0, 0.0, kD, 5.0);
  for (const auto& name : {"deen_gunn", "gunn", "ranz_marshall"}) {
    const auto k = evaluate(name, b, constants(5.0));
    EXPECT_TRUE(close(k[0], 125.0 * 2.0 * std::numbers::pi * kMu * kD, 1e-14)) << name;
  }
}

TEST(MassTransfer, SchmidtNumberEntersAsPublished) {
  // Deen-Gunn at eps 0.6, slip 0.5, Sc 0.7 (python3): 1.3537824490455973e-05
  Batch b;
  b.add(0.6, 0.5, kD, 5.0);
  SceneConstants c = constants(5.0);
  c.schmidt = 0.7;
  EXPECT_TRUE(close(evaluate("deen_gunn", b, c)[0], 1.3537824490455973e-05, 1e-11));
}

TEST(MassTransfer, CoarseGrainingScalesByCgCubed) {
  for (const auto& [name, ref] : kReference) {
    const auto one = evaluate(name, pointsBatch(1.0), constants(1.0));
    for (double cg : {2.0, 5.0, 7.5}) {
      const auto parcel = evaluate(name, pointsBatch(cg), constants(cg));
      for (std::size_t i = 0; i < one.size(); ++i) {
        EXPECT_TRUE(close(parcel[i], cg * cg * cg * one[i], 1e-12)) << name << " cg " << cg;
      }
    }
  }
}

}  // namespace
}  // namespace cosim::models::test
