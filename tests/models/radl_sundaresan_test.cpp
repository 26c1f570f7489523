// Radl & Sundaresan (2014) filtered correction: continuity of the tabulated pieces, limit as the
// cell shrinks, terminal velocity, and the filtered Beetstra law against independent values.
#include "cosim/models/drag/radl_sundaresan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

double jump(double (*f)(double), double x) {
  const double left = f(std::nextafter(x, 0.0));
  const double right = f(x);
  return std::abs(right - left) / std::max(std::abs(left), std::abs(right));
}

// The published coefficients are rounded to 3-4 digits: h is continuous to 0.11 % at every end.
TEST(RadlSundaresan, HIsContinuousAtEveryIntervalEnd) {
  for (double x : {0.03, 0.08, 0.12, 0.18, 0.34, 0.48, 0.55}) {
    EXPECT_LT(jump(radlSundaresanH, x), 2e-3) << "h at phi = " << x;
  }
}

// a is continuous to 0.2 % at 0.10, 0.18, 0.25 and to 5 % at 0.40 (the cubic ends at 1.878 against
// the constant 1.79). The table's dilute constant 21.51 (phi < 0.016) does NOT join the cubic
// (2.465 at 0.016): reported as a table problem, see docs/models.md.
TEST(RadlSundaresan, AIsContinuousAtItsInteriorEnds) {
  for (double x : {0.10, 0.18, 0.25}) EXPECT_LT(jump(radlSundaresanA, x), 2e-3) << x;
  EXPECT_LT(jump(radlSundaresanA, 0.40), 0.05);
}

TEST(RadlSundaresan, CorrectionTendsToOneAsTheCellShrinks) {
  const double L_c = 0.01;
  for (double phi : {0.0, 0.02, 0.1, 0.3, 0.45, 0.6}) {
    double previous = 0.0;
    for (double Delta : {1.0, 1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-9}) {
      const double corr = radlSundaresanCorrection(phi, L_c, Delta);
      EXPECT_GT(corr, 0.0);
      EXPECT_LE(corr, 1.0);
      EXPECT_GE(corr, previous) << "not monotone in Delta at phi " << phi;
      previous = corr;
    }
    EXPECT_NEAR(radlSundaresanCorrection(phi, L_c, 1e-12), 1.0, 1e-8) << phi;
  }
}

TEST(RadlSundaresan, CorrectionStaysInZeroOneForEveryVolumeFraction) {
  for (double phi = 0.0; phi < 1.0; phi += 0.001) {
    for (double Delta : {1e-6, 1e-3, 1.0, 1e3}) {
      const double corr = radlSundaresanCorrection(phi, 1e-3, Delta);
      ASSERT_TRUE(corr > 0.0 && corr <= 1.0) << "phi " << phi << " Delta " << Delta;
    }
  }
}

// Terminal velocities from a log-bisection in python on (rho_p - rho) g pi d^3/6 =
// 3 pi mu d u F(1, rho d u / mu) with Beetstra's F; rho_p 1750, rho 1.12, mu 1.8e-5, g 9.81.
TEST(RadlSundaresan, TerminalVelocityMatchesIndependentSolution) {
  EXPECT_TRUE(
      close(beetstraTerminalVelocity(300e-6, 1750, 1.12, 1.8e-5, 9.81), 1.7624912237170847, 1e-10));
  EXPECT_TRUE(
      close(beetstraTerminalVelocity(5e-3, 1750, 1.12, 1.8e-5, 9.81), 12.930956948317188, 1e-10));
  // Stokes regime: (rho_p - rho) g d^2 / (18 mu) = 1748.88 * 9.81 * 1e-14 / 3.24e-4
  EXPECT_TRUE(close(beetstraTerminalVelocity(1e-7, 1750, 1.12, 1.8e-5, 9.81),
                    1748.88 * 9.81 * 1e-14 / 3.24e-4, 1e-6));
}

TEST(RadlSundaresan, LengthScaleIsUt43OverG13TimesD23) {
  // L_c = (u_t^2/g) (u_t^2/(g d))^(-2/3) = u_t^(2/3) d^(2/3) / g^(1/3): u_t 2, d 1e-3, g 8:
  // 2^(2/3) * 1e-2 / 2 = 0.007937005259840996
  EXPECT_NEAR(radlSundaresanLength(2.0, 8.0, 1e-3), 0.007937005259840996, 1e-15);
}

// Filtered Beetstra (k = 0.05, cg = 5, particle_density 1750) at (eps, slip, cell size):
// python3 tests/models/reference_values.py: K_beetstra * corr * exp(0.05 (1 - 5)).
TEST(RadlSundaresan, FilteredBeetstraMatchesIndependentValues) {
  const double points[5][3] = {
      {0.6, 0.5, 1e-4}, {0.4, 2.0, 1e-3}, {0.95, 1.0, 4e-3}, {0.75, 0.2, 1e-2}, {0.5, 5.0, 0.1}};
  const double expected[5] = {3.845857140381904e-05, 9.2226003803052119e-05, 1.3207397581988376e-05,
                              1.0715331135622811e-05, 2.0396379123687548e-05};
  Parameters p("beetstra");
  p.setText("filtered", "true");
  p.setText("parcel_size_factor", "true");  // the reference values include exp(0.05 (1 - 5))
  p.set("particle_density", kRhoP);
  auto law = Registry::instance().makeDrag("beetstra", p);
  Batch b;
  for (const auto& q : points) b.add(q[0], q[1], kD, 5.0, kRho, kMu, q[2]);
  std::vector<double> K(5);
  law->coefficients(b.view(), constants(5.0), K.data());
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(close(K[i], expected[i], 1e-10)) << i << ": " << K[i];
}

// Terminal velocity from the reference gas (1.12 kg/m3, 1.8e-5 Pa s) or from the parcel's own gas
// (1.5 kg/m3, 2e-5 Pa s); eps 0.6, slip 0.5, cell 4 mm, cg 5, k 0.05 (python3
// tests/models/reference_values.py).
TEST(RadlSundaresan, TerminalVelocityFromReferenceOrLocalGas) {
  Parameters local("beetstra");
  local.setText("filtered", "true");
  local.setText("parcel_size_factor", "true");  // k 0.05 in the reference values
  local.set("particle_density", kRhoP);
  Parameters ref = local;
  ref.set("reference_fluid_density", kRho);
  ref.set("reference_fluid_viscosity", kMu);
  Batch b;
  b.add(0.6, 0.5, kD, 5.0, 1.5, 2.0e-5, 4e-3);
  double K_local = 0, K_ref = 0;
  Registry::instance()
      .makeDrag("beetstra", local)
      ->coefficients(b.view(), constants(5.0), &K_local);
  Registry::instance().makeDrag("beetstra", ref)->coefficients(b.view(), constants(5.0), &K_ref);
  EXPECT_TRUE(close(K_local, 2.6122240879227543e-05, 1e-10)) << K_local;
  EXPECT_TRUE(close(K_ref, 2.7015222887620972e-05, 1e-10)) << K_ref;
}

TEST(RadlSundaresan, ParcelSizeFactorAloneIsExpK1MinusCg) {
  Parameters plain("beetstra");
  Parameters factor("beetstra");
  factor.set("k", 0.1);
  auto a = Registry::instance().makeDrag("beetstra", plain);
  auto b = Registry::instance().makeDrag("beetstra", factor);
  Batch batch;
  batch.add(0.5, 1.0, kD, 4.0);
  double Ka = 0, Kb = 0;
  a->coefficients(batch.view(), constants(4.0), &Ka);
  b->coefficients(batch.view(), constants(4.0), &Kb);
  EXPECT_TRUE(close(Kb / Ka, std::exp(-0.3), 1e-14));
}

}  // namespace
}  // namespace cosim::models::test
