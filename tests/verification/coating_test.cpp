// Verification 3 and 4d/4e: grains held still (LIGGGHTS, no integrator) in a uniform precursor
// field (analytic fluid), deen_gunn mass transfer, box coating zone (scenarios/verify-coating).
// Reference, paper Eq. 7 by hand (d = 300 um, eps = 0.6, |u - v| = 0.5 m/s, rho = 1.12 kg/m3,
// mu = 1.8e-5 Pa s, Sc = 1, Y = 0.011, t = 0.05 s):
//   Re  = 1.12 * 0.6 * 3e-4 * 0.5 / 1.8e-5 = 5.6
//   Sh  = (7 - 6 + 1.8)(1 + 0.17 * 5.6^0.2) + (1.33 - 1.386 + 0.4176) * 5.6^0.7 = 4.679510
//   K_m = Sh D / d = 4.679510 * (1.8e-5 / 1.12) / 3e-4 = 0.2506880 m/s
//   dm/dt = K_m Y rho pi d^2 = 8.732461e-10 kg/s;  m(0.05 s) = 4.366231e-11 kg per grain
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "cosim/link/fields.h"
#include "run_scene.h"

using cosim::verification::runScene;
namespace field = cosim::field;

namespace {

constexpr double kCoatingPerGrain = 4.366231e-11;  // kg after 0.05 s (hand value above)

// Coating mass per grain id (ids 1..4 at z = 0.01, 0.02, 0.03, 0.04 m).
std::map<std::int64_t, double> coatingById(const cosim::orchestrator::RunResult& r) {
  std::map<std::int64_t, double> m;
  const auto& c = r.final_state.get(field::coating_mass);
  for (std::size_t i = 0; i < r.final_state.size(); ++i) m[r.final_state.ids[i]] = c[i];
  return m;
}

void expectBalanceClosed(const cosim::orchestrator::RunResult& r) {
  const double removed = r.totals.at("precursor_removed_kg");
  EXPECT_TRUE(std::isfinite(removed));
  EXPECT_NEAR(r.totals.at("coating_credited_kg"), removed, 1e-12 * std::max(removed, 1e-30));
  EXPECT_NEAR(r.totals.at("coating_on_particles_kg"), removed, 1e-12 * std::max(removed, 1e-30));
}

}  // namespace

TEST(Coating, GrowsAsEquation7InsideTheZoneAndNotOutside) {
  auto r = runScene("verify-coating", {}, "coating");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  auto m = coatingById(r);
  ASSERT_EQ(m.size(), 4u);
  EXPECT_NEAR(m[1], kCoatingPerGrain, 1e-3 * kCoatingPerGrain);  // inside the zone (z <= 0.025)
  EXPECT_NEAR(m[2], kCoatingPerGrain, 1e-3 * kCoatingPerGrain);
  EXPECT_EQ(m[3], 0.0);  // outside
  EXPECT_EQ(m[4], 0.0);
  expectBalanceClosed(r);
  EXPECT_NEAR(r.totals.at("precursor_removed_kg"), 2 * kCoatingPerGrain, 1e-3 * kCoatingPerGrain);
}

TEST(Coating, ZoneContainingAllGrainsCoatsEachAlike) {
  auto r = runScene("verify-coating", {"zone_zmin=-1", "zone_zmax=1"}, "coating-all");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  for (auto [id, mass] : coatingById(r)) EXPECT_NEAR(mass, kCoatingPerGrain, 1e-3 * kCoatingPerGrain) << id;
  expectBalanceClosed(r);
}

TEST(Coating, ZoneContainingNoGrainCoatsNothing) {
  auto r = runScene("verify-coating", {"zone_zmin=0.5", "zone_zmax=0.6"}, "coating-none");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  for (auto [id, mass] : coatingById(r)) EXPECT_EQ(mass, 0.0) << id;
  EXPECT_EQ(r.totals.at("precursor_removed_kg"), 0.0);
  expectBalanceClosed(r);
}

TEST(Coating, ZeroPrecursorGivesNoCoatingAndNoNaN) {
  auto r = runScene("verify-coating", {"Y=0", "zone_zmin=-1", "zone_zmax=1"}, "coating-y0");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  for (auto [id, mass] : coatingById(r)) EXPECT_EQ(mass, 0.0) << id;
  for (const auto& [name, value] : r.totals) EXPECT_TRUE(std::isfinite(value)) << name;
  EXPECT_EQ(r.totals.at("precursor_removed_kg"), 0.0);
  expectBalanceClosed(r);
}
