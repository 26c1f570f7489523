// models.drag.undisturbed_velocity: self_disturbance (the parcel's own disturbance of the gas it
// samples removed), against numbers computed by hand with python3 from the formulas of
// docs/models.md (the script is in the comment of each test):
//   G = 1 / (eps_f mu Delta / c_v + eps rho |u_f| Delta^2 / c_a), eps_f = (1 + eps)/2,
//   c_v = (2/3) 0.2527310, c_a = 1
//   w = min(1, V_parcel / ((1 - eps) Delta^3)),  K_eff = K(u_und) / (1 - w K G)
#include "cosim/models/drag/undisturbed_velocity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cosim/models/registry.h"
#include "support.h"

namespace cosim::models::test {
namespace {

constexpr double kPi = std::numbers::pi;

// One parcel, gas (0, 0, u), parcel velocity (0, 0, v).
Batch lone(double d, double Delta, double eps, double u, double v) {
  Batch b;
  b.add(eps, 0.0, d, 1.0, kRho, kMu, Delta);
  b.fluid_velocity = {0.0, 0.0, u};
  b.velocity = {0.0, 0.0, v};
  return b;
}

std::unique_ptr<DragLaw> corrected(const std::string& law) {
  Parameters p("models.drag");
  p.setText("undisturbed_velocity", "self_disturbance");
  return Registry::instance().makeDrag(law, p);
}

TEST(UndisturbedVelocity, ResponseCoefficientsAreTheLatticeGreensFunction) {
  // c_v = (2/3) x Watson's simple-cubic Green's function at the origin, 1.516386/6 = 0.2527310
  EXPECT_NEAR(SelfDisturbance::kViscous, 2.0 / 3.0 * 0.2527310, 1e-6);
  // viscous limit |u_f| = 0: G = c_v / (eps_f mu Delta)
  EXPECT_NEAR(SelfDisturbance::response(1.0, 1e-3, 1000.0, 0.0, 0.01), 0.168487 / 1e-5,
              1e-6 / 1e-5);
  // advective limit: G -> c_a / (eps rho |u| Delta^2)
  EXPECT_NEAR(SelfDisturbance::response(1.0, 1e-12, 1.0, 2.0, 0.1) * 2.0 * 0.01, 1.0, 1e-9);
}

TEST(UndisturbedVelocity, StokesSphereAloneInACellOfTwoDiameters) {
  // python3: d = 20e-6, Delta = 40e-6, eps = 1 - pi/6 d^3/Delta^3 = 0.934550153050213,
  // u = 0.01, K = 3 pi mu d = 3.39292006587698e-09, G = 240951001.031883,
  // K G = 0.81752748629422, K_eff = 1.85941432875076e-08 (5.5 x Stokes)
  const double d = 20e-6, Delta = 40e-6;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  Batch b = lone(d, Delta, eps, 0.01, 0.0);
  EXPECT_NEAR(SelfDisturbance::share(d / 2, eps, Delta), 1.0, 1e-12);  // alone in its cell
  double K = 0.0;
  corrected("stokes")->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K, 1.85941432875076e-08, 1e-12 * 1.9e-8);
}

TEST(UndisturbedVelocity, SchillerNaumannIsEvaluatedAtTheUndisturbedSlip) {
  // python3: d = 180e-6, Delta = 540e-6 (3 d), eps = 0.980607452755619, u = 0.86, v = 0.01,
  // G = 3007041.53266783; K at the sampled slip 5.17877114061519e-08, at the undisturbed slip
  // (fixed point) 5.4572654609761e-08, K G = 0.164102238959488, K_eff = 6.52862791997789e-08
  const double d = 180e-6, Delta = 540e-6;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  Batch b = lone(d, Delta, eps, 0.86, 0.01);
  double K = 0.0, K_plain = 0.0;
  Registry::instance()
      .makeDrag("schiller_naumann", Parameters("d"))
      ->coefficients(b.view(), constants(1.0), &K_plain);
  EXPECT_NEAR(K_plain, 5.17877114061519e-08, 1e-11 * 5.2e-8);
  corrected("schiller_naumann")->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K, 6.52862791997789e-08, 1e-11 * 6.5e-8);
}

TEST(UndisturbedVelocity, FadesWithTheParcelsShareOfADenseCell) {
  // python3: Stokes, d = 300e-6 in a 4 mm cell at eps = 0.5, u = 0.3: w = 0.000441786466911065,
  // G = 332391.68206397, a = w K / (1/G + K (1 - w)/w) = 1.90289846455796e-07,
  // K_eff / K = 1.00000019028988
  const double d = 300e-6, Delta = 4e-3;
  EXPECT_NEAR(SelfDisturbance::share(d / 2, 0.5, Delta), 0.000441786466911065, 1e-15);
  Batch b = lone(d, Delta, 0.5, 0.3, 0.0);
  double K = 0.0;
  corrected("stokes")->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K / (3.0 * kPi * kMu * d), 1.00000019028988, 1e-13);
}

TEST(UndisturbedVelocity, InAPackedCellTheOthersDragTakesTheDisturbance) {
  // The fluidized-bed cell: 1.5 mm parcels in 4 mm cells at eps 0.4, gas 0.05 m/s, K = 1e-4 kg/s
  // (Beetstra-sized): K G = 152.1 but w = 0.0460194236365692 and the other parcels' drag gives
  // a = 0.00221924416231722 (-> w^2/(1 - w) = 0.00221994808313081 for K G -> infinity).
  const double d = 1.5e-3, Delta = 4e-3;
  const double w = SelfDisturbance::share(d / 2, 0.4, Delta);
  EXPECT_NEAR(w, 0.0460194236365692, 1e-14);
  const double G = SelfDisturbance::response(0.4, kMu, kRho, 0.05, Delta);
  EXPECT_NEAR(1e-4 * G, 152.083788425505, 1e-9);
  EXPECT_NEAR(SelfDisturbance::coupling(1e-4, G, w), 0.00221924416231722, 1e-15);
}

TEST(UndisturbedVelocity, SelfCouplingIsBoundedAtPointNine) {
  // A 1 mm Stokes sphere in a cell just larger than itself, gas at rest: K G = 3 pi c_v d / Delta
  // / eps >> 1; capped at 0.9, so K_eff = 10 K exactly.
  const double d = 1e-3, Delta = 1.05e-3;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  Batch b = lone(d, Delta, eps, 0.0, -0.01);
  double K = 0.0;
  corrected("stokes")->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K / (3.0 * kPi * kMu * d), 10.0, 1e-12);
}

TEST(UndisturbedVelocity, NoneIsTheLawItselfAndLostParcelsGetNoDrag) {
  const double d = 180e-6, Delta = 540e-6;
  Batch b = lone(d, Delta, 0.98, 0.86, 0.01);
  Parameters none("models.drag");
  none.setText("undisturbed_velocity", "none");
  double K_none = 0.0, K_plain = 0.0;
  Registry::instance()
      .makeDrag("schiller_naumann", none)
      ->coefficients(b.view(), constants(1.0), &K_none);
  Registry::instance()
      .makeDrag("schiller_naumann", Parameters("d"))
      ->coefficients(b.view(), constants(1.0), &K_plain);
  EXPECT_EQ(K_none, K_plain);

  const std::vector<char> lost = {1};
  ParcelBatch v = b.view();
  v.lost = lost.data();
  double K = 1.0;
  corrected("schiller_naumann")->coefficients(v, constants(1.0), &K);
  EXPECT_EQ(K, 0.0);
  // the transient estimate too, lattice and calibrated (a lost parcel has no cell, G = 0)
  const double H[3] = {0.0, 0.0, 1e-9};
  v.built_up_force = H;
  for (double beta : {0.0, 0.01}) {
    Parameters t("models.drag");
    t.setText("undisturbed_velocity", "self_disturbance_transient");
    t.set("self_disturbance_offset", beta);
    K = 1.0;
    Registry::instance().makeDrag("schiller_naumann", t)->coefficients(v, constants(1.0), &K);
    EXPECT_EQ(K, 0.0) << "beta " << beta;
  }
}

TEST(UndisturbedVelocity, DeclaresCellSizeAndRejectsUnknownChoices) {
  auto law = corrected("stokes");
  EXPECT_EQ(law->name(), "stokes");
  const auto f = law->requiredFields();
  for (const char* x : {"cell_size", "voidage", "fluid_density", "fluid_velocity"}) {
    EXPECT_NE(std::find(f.begin(), f.end(), x), f.end()) << x;
  }
  Parameters bad("models.drag");
  bad.setText("undisturbed_velocity", "selfdisturbance");
  try {
    Registry::instance().makeDrag("beetstra", bad);
    FAIL() << "expected an error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("known: none, self_disturbance"), std::string::npos)
        << e.what();
  }
  // the law's own parameters are still checked (the key is removed before the law sees it)
  Parameters typo("models.drag");
  typo.setText("undisturbed_velocity", "self_disturbance");
  typo.set("swich_voidage", 0.8);
  EXPECT_THROW(Registry::instance().makeDrag("gidaspow", typo), ModelError);
}

// self_disturbance_transient: K_eff = K (1 + x), x = G H . (u_s - v) / |u_s - v|^2 for a lone
// parcel, H the built-up force the coupler keeps (wake_buildup_test.cpp). The Stokes sphere of
// StokesSphereAloneInACellOfTwoDiameters: K = 3 pi mu d = 3.39292006587698e-09,
// G = 240951001.031883, steady K_eff = 1.85941432875076e-08, steady force F* = K_eff 0.01.
std::unique_ptr<DragLaw> transient(const std::string& law) {
  Parameters p("models.drag");
  p.setText("undisturbed_velocity", "self_disturbance_transient");
  return Registry::instance().makeDrag(law, p);
}

double transientK(double Hx, double Hz) {
  const double d = 20e-6, Delta = 40e-6;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  Batch b = lone(d, Delta, eps, 0.01, 0.0);
  const double H[3] = {Hx, 0.0, Hz};
  ParcelBatch v = b.view();
  v.built_up_force = H;
  double K = 0.0;
  transient("stokes")->coefficients(v, constants(1.0), &K);
  return K;
}

TEST(UndisturbedVelocity, TransientFollowsTheBuiltUpForce) {
  const double K = 3.39292006587698e-09, Fs = 1.85941432875076e-08 * 0.01;
  // nothing built up yet (a new parcel): the law itself
  EXPECT_NEAR(transientK(0.0, 0.0), K, 1e-12 * K);
  // fully built up (H = F*): the steady estimate
  EXPECT_NEAR(transientK(0.0, Fs), 1.85941432875076e-08, 1e-9 * 1.86e-8);
  // half of it: x = G F* / 2 / 0.01 = 2.240138719227612, K (1 + x) = 1.0993531676692302e-08
  EXPECT_NEAR(transientK(0.0, 0.5 * Fs), 1.0993531676692302e-08, 1e-9 * 1.1e-8);
  // across the slip it is not applied (the factor acts along the sampled slip)
  EXPECT_NEAR(transientK(Fs, 0.0), K, 1e-12 * K);
  // bounds: K_eff in [0.1 K, 10 K] (an old wake far larger than the slip, either way)
  EXPECT_NEAR(transientK(0.0, 100 * Fs), 10 * K, 1e-12 * K);
  EXPECT_NEAR(transientK(0.0, -100 * Fs), 0.1 * K, 1e-12 * K);
}

TEST(UndisturbedVelocity, TransientNeedsTheBuiltUpForceAndThePosition) {
  auto law = transient("stokes");
  const auto f = law->requiredFields();
  EXPECT_NE(std::find(f.begin(), f.end(), "position"), f.end());
  Batch b = lone(20e-6, 40e-6, 0.93, 0.01, 0.0);
  double K = 0.0;
  try {
    law->coefficients(b.view(), constants(1.0), &K);
    FAIL() << "expected an error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("self_disturbance_transient"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("built-up force"), std::string::npos) << e.what();
  }
}

TEST(UndisturbedVelocity, TransientFadesInAPackedCellAsTheSteadyOne) {
  // fully built up (H = the steady force) in a packed cell: the same K_eff as the steady estimate
  Batch b;
  b.add(0.4, 0.02, 1.5e-3, 1.0, kRho, kMu, 4e-3);
  double steady = 0.0, K = 0.0;
  corrected("beetstra")->coefficients(b.view(), constants(1.0), &steady);
  std::vector<double> H(3);
  for (int j = 0; j < 3; ++j) H[j] = steady * (b.fluid_velocity[j] - b.velocity[j]);
  ParcelBatch v = b.view();
  v.built_up_force = H.data();
  transient("beetstra")->coefficients(v, constants(1.0), &K);
  EXPECT_NEAR(K, steady, 1e-9 * steady);
}

// Calibrated for the gas solver (self_disturbance_gain gamma, self_disturbance_offset beta):
// K_eff = K / (1 + beta f - gamma a), f = a / (K G). Numbers by python3 from those formulas.
std::unique_ptr<DragLaw> calibrated(const std::string& choice, double gamma, double beta) {
  Parameters p("models.drag");
  p.setText("undisturbed_velocity", choice);
  p.set("self_disturbance_gain", gamma);
  p.set("self_disturbance_offset", beta);
  return Registry::instance().makeDrag("stokes", p);
}

TEST(UndisturbedVelocity, CalibratedGainAndOffsetOfTheGasSolver) {
  // the Stokes sphere in cells of two diameters: a = 0.8175274862942198; gamma 1.02, beta 0.01:
  // K_eff = K / (1.01 - 1.02 a) = 1.9264604988531e-08 (the lattice's 1.85941432875076e-08)
  const double d = 20e-6, Delta = 40e-6;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  double K = 0.0;
  Batch b = lone(d, Delta, eps, 0.01, 0.0);
  calibrated("self_disturbance", 1.02, 0.01)->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K, 1.9264604988531e-08, 1e-12 * 1.9e-8);
  // the same slip seen from a moving parcel (gas 0.005, parcel -0.005): the same factor on K,
  // since both corrections act on the slip (G is evaluated at |u_f| = 0.005, so compare with
  // gamma 1, beta 0 at that state)
  Batch m = lone(d, Delta, eps, 0.005, -0.005);
  double Kc = 0.0, K0 = 0.0;
  calibrated("self_disturbance", 1.02, 0.01)->coefficients(m.view(), constants(1.0), &Kc);
  calibrated("self_disturbance", 1.0, 0.0)->coefficients(m.view(), constants(1.0), &K0);
  corrected("stokes")->coefficients(m.view(), constants(1.0), &K);
  EXPECT_NEAR(K0, K, 1e-14 * K);  // gamma 1, beta 0 is the lattice estimate
  const double kStokes = 3.0 * kPi * kMu * d;
  const double a = 1.0 - kStokes / K0;
  EXPECT_NEAR(Kc, kStokes / (1.01 - 1.02 * a), 1e-12 * Kc);
  // gamma a is capped at 0.9 as a is: gamma 2, beta 0.05 gives K / 0.15
  calibrated("self_disturbance", 2.0, 0.05)->coefficients(b.view(), constants(1.0), &K);
  EXPECT_NEAR(K / kStokes, 1.0 / 0.15, 1e-12);
}

TEST(UndisturbedVelocity, CalibratedTransientAndDenseFade) {
  // transient, half of the lattice's steady force built up (H = 0.5 K_eff 0.01):
  // u_und = (0.01 + gamma G H) / (1 + beta), K_eff = K u_und / 0.01 = 1.1035191989018426e-08
  const double d = 20e-6, Delta = 40e-6;
  const double eps = 1.0 - kPi / 6.0 * std::pow(d / Delta, 3);
  Batch b = lone(d, Delta, eps, 0.01, 0.0);
  const double H[3] = {0.0, 0.0, 0.5 * 1.85941432875076e-08 * 0.01};
  ParcelBatch v = b.view();
  v.built_up_force = H;
  double K = 0.0;
  calibrated("self_disturbance_transient", 1.02, 0.01)->coefficients(v, constants(1.0), &K);
  EXPECT_NEAR(K, 1.1035191989018426e-08, 1e-9 * 1.1e-8);
  // in a dense cell the offset fades as a does: d = 300 um in a 4 mm cell at eps 0.5, u = 0.3,
  // f = 1.1248654590227135e-05, a = 1.9028984645579644e-07; gamma 1.5, beta 0.2:
  // K_eff / K = 1 / (1 + 0.2 f - 1.5 a) = 0.9999980357077101 (without the fade it would be 0.83)
  Batch dense = lone(300e-6, 4e-3, 0.5, 0.3, 0.0);
  calibrated("self_disturbance", 1.5, 0.2)->coefficients(dense.view(), constants(1.0), &K);
  EXPECT_NEAR(K / (3.0 * kPi * kMu * 300e-6), 0.9999980357077101, 1e-13);
}

TEST(UndisturbedVelocity, CalibrationKeysAreCheckedAndNeedACorrection) {
  auto message = [](const std::string& choice, const std::string& key, double value) {
    Parameters p("models.drag");
    if (!choice.empty()) p.setText("undisturbed_velocity", choice);
    p.set(key, value);
    try {
      Registry::instance().makeDrag("stokes", p);
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // without a choice (the correction off by default): refused, named, with what to do
  std::string m = message("", "self_disturbance_offset", 0.01);
  EXPECT_NE(m.find("self_disturbance_offset"), std::string::npos) << m;
  EXPECT_NE(m.find("'self_disturbance'"), std::string::npos) << m;
  // with an explicit `none` the calibration is kept and the law is the law itself
  EXPECT_EQ(message("none", "self_disturbance_gain", 1.02), "");
  // out of range: the key and the range
  m = message("self_disturbance", "self_disturbance_gain", 5.0);
  EXPECT_NE(m.find("self_disturbance_gain"), std::string::npos) << m;
  m = message("self_disturbance_transient", "self_disturbance_offset", -0.5);
  EXPECT_NE(m.find("self_disturbance_offset"), std::string::npos) << m;
  EXPECT_EQ(message("self_disturbance", "self_disturbance_offset", 0.02), "");
}

}  // namespace
}  // namespace cosim::models::test
