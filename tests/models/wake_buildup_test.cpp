// The build-up in time of a parcel's own disturbance (cosim/models/drag/wake_buildup.h), for
// models.drag.undisturbed_velocity: self_disturbance_transient. Reference numbers from
// scenarios/verify-wake/kernel.py (scipy): S(tau) = C(tau) / C(inf) with C the integral of the
// lattice's on-site heat kernel [e^-2s I0(2s)]^3, and the exact response of the lattice after m
// implicit-Euler steps (computed there from the Bessel product directly, not from the fit).
// Tolerances: a few times the fit's error at each point (printed by kernel.py).
#include "cosim/models/drag/wake_buildup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "support.h"

namespace cosim::models::test {
namespace {

TEST(WakeKernel, BuildUpIsTheLatticeHeatKernelIntegral) {
  // kernel.py: S(tau) exact | fit error
  EXPECT_NEAR(WakeKernel::buildup(0.0), 0.0, 1e-9);
  EXPECT_NEAR(WakeKernel::buildup(0.1), 0.3001006477, 2.5e-3);   // fit -8.7e-4
  EXPECT_NEAR(WakeKernel::buildup(1.0), 0.8073465112, 4e-4);     // -1.2e-4
  EXPECT_NEAR(WakeKernel::buildup(2.0), 0.8699354572, 4e-5);     // -1.0e-5
  EXPECT_NEAR(WakeKernel::buildup(32.0), 0.9685345024, 3e-5);    // -7.7e-6
  EXPECT_NEAR(WakeKernel::buildup(200.0), 0.9874345657, 1e-5);   // -2.7e-6
  EXPECT_NEAR(WakeKernel::buildup(1000.0), 0.9943819731, 1e-5);  // -2.4e-6
  // the t^-1/2 tail: 1 - S -> 2 (4 pi)^-3/2 / sqrt(tau) / C(inf) = 0.0056177 at tau = 1000
  EXPECT_NEAR(1.0 - WakeKernel::buildup(1000.0), 5.6177e-3, 3e-5);
  double sum = 0.0, slope = 0.0;
  for (const auto& m : WakeKernel::modes()) {
    EXPECT_GT(m.weight, 0.0);
    EXPECT_GE(m.lambda, 0.0);
    EXPECT_LE(m.lambda, 12.0);  // the 7-point Laplacian's spectrum
    sum += m.weight;
    slope += m.weight * m.lambda;
  }
  EXPECT_NEAR(sum, 1.0, 1e-9);                         // S(0) = 0
  EXPECT_NEAR(slope * 0.2527310098586630, 1.0, 1e-9);  // dS/dtau(0) = 1 / C(inf), Watson / 6
}

TEST(WakeKernel, ImplicitStepsAreTheLatticeImplicitEulerResponse) {
  // kernel.py: exact lattice after m implicit-Euler steps of tau_s | fit error
  EXPECT_NEAR(WakeKernel::buildupImplicit(1, 0.32), 0.47248689, 1e-3);   // -3.1e-4
  EXPECT_NEAR(WakeKernel::buildupImplicit(5, 0.32), 0.83647904, 1e-4);   // -3.4e-5
  EXPECT_NEAR(WakeKernel::buildupImplicit(1, 2.0), 0.76711071, 2e-4);    // -5.9e-5
  EXPECT_NEAR(WakeKernel::buildupImplicit(5, 2.0), 0.93855042, 2e-5);    // -3.8e-6
  EXPECT_NEAR(WakeKernel::buildupImplicit(20, 0.89), 0.95691801, 4e-5);  // +9.8e-6
}

// One parcel per id at position x (z only), gas u_z, parcel velocity v_z, cell Delta.
struct Scene {
  ParcelArrays a;
  std::vector<std::int64_t> ids;
  std::vector<char> lost;
  std::vector<double> K;
  void add(std::int64_t id, double z, double u, double v, double Delta, double mu = 1.8e-5,
           double rho = 1.2) {
    ids.push_back(id);
    a.position.insert(a.position.end(), {0.0, 0.0, z});
    a.velocity.insert(a.velocity.end(), {0.0, 0.0, v});
    a.fluid_velocity.insert(a.fluid_velocity.end(), {0.0, 0.0, u});
    a.radius.push_back(10e-6);
    a.voidage.push_back(1.0);
    a.fluid_density.push_back(rho);
    a.fluid_viscosity.push_back(mu);
    a.cell_size.push_back(Delta);
    lost.push_back(0);
    K.push_back(1e-9);
  }
  ParcelBatch view() const {
    ParcelBatch b = a.view();
    b.lost = lost.data();
    return b;
  }
};

// H_z of parcel i after startInterval.
double builtUp(WakeBuildup& w, const Scene& s, std::size_t i) {
  return w.startInterval(s.ids, s.view(), constants(1.0))[3 * i + 2];
}

TEST(WakeBuildup, ViscousBuildUpFollowsTheLatticeImplicitEulerResponse) {
  // still gas, parcel falling at 0.01 m/s: F = K (0 - v) = 1e-11 N up; nu = mu/rho = 1.5e-5,
  // Delta = 40 um, dt = 2 Delta^2 / nu (tau_s = 2)
  Scene s;
  const double Delta = 40e-6, nu = 1.8e-5 / 1.2, dt = 2.0 * Delta * Delta / nu, F = 1e-11;
  s.add(7, 0.0, 0.0, -0.01, Delta);
  WakeBuildup w;
  EXPECT_EQ(builtUp(w, s, 0), 0.0);  // a new parcel: its gas has not felt it yet
  const double exact[] = {0.76711071, 0.88222424, 0, 0, 0.93855042};  // kernel.py, m = 1, 2, 5
  for (int m = 1; m <= 5; ++m) {
    w.recordInterval(s.ids, s.view(), s.K.data(), dt);
    const double H = builtUp(w, s, 0);
    if (exact[m - 1] > 0) {
      EXPECT_NEAR(H / F, exact[m - 1], 2e-4) << "m = " << m;
    }
  }
}

TEST(WakeBuildup, AdvectiveLimitIsTheUpwindOutflow) {
  // no viscosity (1e-20): the flow sweeps the cell's momentum out at |u| / Delta, implicit:
  // H / F = 1 - (1 + |u| dt / Delta)^-m = 1 - 1.5^-3 after 3 steps of |u| dt / Delta = 0.5
  // (the drift walk's rate (sqrt(1 + Re) - 1)^2 nu / Delta^2 is |u| / Delta to 2 sqrt(1/Re) = 2e-8)
  Scene s;
  s.add(1, 0.0, 0.1, 0.0, 1e-3, 1e-20);
  WakeBuildup w;
  const double F = 1e-9 * 0.1;
  for (int m = 1; m <= 3; ++m) {
    builtUp(w, s, 0);
    w.recordInterval(s.ids, s.view(), s.K.data(), 5e-3);
  }
  EXPECT_NEAR(builtUp(w, s, 0) / F, 1.0 - std::pow(1.5, -3), 1e-7);
}

TEST(WakeBuildup, AtLowCellReynoldsNumberTheFlowCutsOnlyTheTail) {
  // Re = |u| Delta / nu = 0.05: the flow cuts the diffusion tail at |u|^2 / (4 nu) (c = Re^2/4 =
  // 6.2e-4 in nu / Delta^2), so the first steps are the viscous ones (kernel.py: 0.76711071 after
  // one step of tau_s = 2) and the end is still the whole force
  const double Delta = 40e-6, nu = 1.8e-5 / 1.2, u = 0.05 * nu / Delta,
               dt = 2.0 * Delta * Delta / nu;
  Scene s;
  s.add(2, 0.0, u, 0.0, Delta);
  WakeBuildup w;
  builtUp(w, s, 0);
  w.recordInterval(s.ids, s.view(), s.K.data(), dt);
  // (the modes slower than c, 0.6 % of the weight, are renormalised onto the others: 0.7729)
  EXPECT_NEAR(builtUp(w, s, 0) / (1e-9 * u), 0.76711071, 8e-3);
  w.recordInterval(s.ids, s.view(), s.K.data(), 1e9);
  EXPECT_NEAR(builtUp(w, s, 0) / (1e-9 * u), 1.0, 1e-9);
}

// A parcel whose own disturbance has fully built up (one implicit step of 1e9 s: r dt > 2e6 for the
// slowest mode).
WakeBuildup builtUpParcel(Scene& s, double Delta) {
  s.add(3, 0.0, 0.0, -0.01, Delta);
  WakeBuildup w;
  builtUp(w, s, 0);
  w.recordInterval(s.ids, s.view(), s.K.data(), 1e9);
  return w;
}

TEST(WakeBuildup, FullyBuiltUpItIsTheSteadyForce) {
  Scene s;
  WakeBuildup w = builtUpParcel(s, 40e-6);
  EXPECT_NEAR(builtUp(w, s, 0) / 1e-11, 1.0, 1e-9);
}

TEST(WakeBuildup, AParcelEnteringTheNextCellKeepsTheShareTheOldCellsWakeHasThere) {
  const double Delta = 40e-6;
  Scene s;
  WakeBuildup w = builtUpParcel(s, Delta);
  // less than half a cell: same cell, nothing changes
  s.a.position[2] = 0.4 * Delta;
  EXPECT_NEAR(builtUp(w, s, 0) / 1e-11, 1.0, 1e-9);
  // more than half a cell from where it started: the next cell, whose gas holds the lattice
  // Green's function one cell over, 1 - 1 / (6 C(inf)) = 0.340537329550999 of the old wake
  s.a.position[2] = 0.6 * Delta;
  EXPECT_NEAR(builtUp(w, s, 0) / 1e-11, 0.340537329550999, 1e-8);
  // the next call in the same place changes nothing (the cell is now taken to be at +Delta)
  EXPECT_NEAR(builtUp(w, s, 0) / 1e-11, 0.340537329550999, 1e-8);
  // back below +Delta/2: the first cell again, one more step (1 - lambda_i/6 per mode again; the
  // history has no place in it, so going back is one more step, not the first cell's own wake)
  s.a.position[2] = 0.3 * Delta;
  double twice = 0.0;
  for (std::size_t i = 0; i < WakeKernel::kModes; ++i)
    twice += WakeKernel::modes()[i].weight * std::pow(WakeKernel::neighbourShare(i), 2);
  EXPECT_NEAR(builtUp(w, s, 0) / 1e-11, twice, 1e-9);
  EXPECT_NEAR(w.state().at(3).anchor[2], 0.0, 1e-18);
}

TEST(WakeBuildup, LostVanishedAndNewParcels) {
  const double Delta = 40e-6;
  Scene s;
  for (std::int64_t id : {1, 2, 3}) s.add(id, 0.0, 0.0, -0.01, Delta);
  WakeBuildup w;
  w.startInterval(s.ids, s.view(), constants(1.0));
  w.recordInterval(s.ids, s.view(), s.K.data(), 1e9);
  ASSERT_EQ(w.state().size(), 3u);

  // next interval: 2 is gone, 3 is lost (in no cell), 4 is new
  Scene t;
  for (std::int64_t id : {1, 3, 4}) t.add(id, 0.0, 0.0, -0.01, Delta);
  t.lost[1] = 1;
  const auto H = w.startInterval(t.ids, t.view(), constants(1.0));
  EXPECT_NEAR(H[2] / 1e-11, 1.0, 1e-9);  // 1 keeps its history
  EXPECT_EQ(H[5], 0.0);                  // lost: no own disturbance, history dropped
  EXPECT_EQ(H[8], 0.0);                  // new
  EXPECT_EQ(w.state().count(2), 0u);
  EXPECT_EQ(w.state().count(3), 0u);
  EXPECT_EQ(w.state().count(4), 1u);
  w.recordInterval(t.ids, t.view(), t.K.data(), 1e-4);  // the lost one is skipped

  // 3 found again: it starts from nothing
  t.lost[1] = 0;
  EXPECT_EQ(w.startInterval(t.ids, t.view(), constants(1.0))[5], 0.0);
}

TEST(WakeBuildup, TheIntervalIsAdvancedWithTheForceTheGasGot) {
  // The gas takes the drag implicitly, K (U_new - v): the interval's K and v are kept and the
  // force is taken with the gas velocity sampled at the start of the next interval.
  Scene s;
  s.add(5, 0.0, 0.0, -0.01, 40e-6);
  WakeBuildup w;
  builtUp(w, s, 0);
  w.recordInterval(s.ids, s.view(), s.K.data(), 1e9);  // K = 1e-9, v = -0.01
  s.a.fluid_velocity[2] = 0.005;                       // the gas dragged along over the interval
  s.a.velocity[2] = -0.02;                             // the parcel's new velocity: not used
  // F = 1e-9 (0.005 + 0.01) = 1.5e-11, fully built up over 1e9 s
  EXPECT_NEAR(builtUp(w, s, 0) / 1.5e-11, 1.0, 1e-9);
  // nothing recorded since: no further change
  EXPECT_NEAR(builtUp(w, s, 0) / 1.5e-11, 1.0, 1e-9);
}

TEST(WakeBuildup, StateRestoredIsTheSameHistory) {
  Scene s;
  WakeBuildup w = builtUpParcel(s, 40e-6);
  WakeBuildup copy;
  copy.restore(w.state());
  const auto a = w.startInterval(s.ids, s.view(), constants(1.0));
  const auto b = copy.startInterval(s.ids, s.view(), constants(1.0));
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace cosim::models::test
