// Packed bed of fixed parcels, gas through it with the Gidaspow (Ergun branch) drag evaluated
// from the gas samples exactly as the orchestrator would: at steady state the pressure drop
// over the bed is the Ergun equation's within 3 %, at two flows.
//
// Model A at steady state in a uniform bed: 0 = -eps dp/dz - beta u, u = U/eps, which with the
// Gidaspow beta is Ergun: -dp/dz = 150 mu (1-eps)^2 U/(eps^3 d^2) + 1.75 rho (1-eps) U^2/(eps^3 d).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "foam_harness.h"
#include "gas_constants.h"

namespace cosim::test {
namespace {

constexpr double kCell = 0.004;
constexpr double kD = 1.9e-3;  // particle diameter: 8 per 4 mm cell, wholly inside
constexpr double kBottom = 0.020, kTop = 0.060;

std::vector<double> bedLattice() {
  std::vector<double> xyz;
  for (double z = kBottom + 1e-3; z < kTop; z += 2e-3)
    for (double y = 1e-3; y < 0.02; y += 2e-3)
      for (double x = 1e-3; x < 0.02; x += 2e-3) xyz.insert(xyz.end(), {x, y, z});
  return xyz;
}

double ergunPerLength(double U, double eps, double rho) {
  const double a = 150 * gas::mu * (1 - eps) * (1 - eps) * U / (eps * eps * eps * kD * kD);
  const double b = 1.75 * rho * (1 - eps) * U * U / (eps * eps * eps * kD);
  return a + b;
}

double bedPressureDrop(double U) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", std::to_string(U)},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.options_yaml = "{min_voidage: 0.3}";
  cfg.send = {"fluid_velocity", "voidage", "fluid_density", "fluid_viscosity"};
  cfg.receive = {"position", "radius", "velocity", "drag_coefficient"};
  FoamRun run(cfg);

  const auto particles = makeParticles(bedLattice(), kD / 2);
  const double Vp = std::numbers::pi / 6 * kD * kD * kD;
  double drop = 0, previous = -1;
  for (int step = 0; step < 300; ++step) {
    const auto s = run.sample(particles);
    EXPECT_TRUE(s.lost.empty());
    cosim::link::ParticleData terms;
    terms.ids = particles.ids;
    auto& K = terms.field("drag_coefficient");
    K.resize(particles.size());
    const auto& u = s.at.get("fluid_velocity");
    const auto& eps = s.at.get("voidage");
    const auto& rho = s.at.get("fluid_density");
    const auto& mu = s.at.get("fluid_viscosity");
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const double slip = std::hypot(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
      const double e = eps[i];
      const double beta =
          150 * (1 - e) * (1 - e) * mu[i] / (e * kD * kD) + 1.75 * (1 - e) * rho[i] * slip / kD;
      K[i] = beta * Vp / (1 - e);
    }
    const auto a = run.advance(2e-3, terms);
    previous = drop;
    drop = a.fluid().pressure_drop();
    if (step > 20 && std::abs(drop - previous) < 1e-9 * std::abs(drop)) break;
  }
  EXPECT_LT(std::abs(drop - previous), 1e-6 * std::abs(drop)) << "not steady";
  EXPECT_EQ(run.shutdown(), 0);
  return drop;
}

TEST(OpenFoamPackedBed, PressureDropFollowsErgunAtTwoFlows) {
  const double phi = 8 * std::numbers::pi / 6 * kD * kD * kD / (kCell * kCell * kCell);
  const double eps = 1 - phi;
  const double L = kTop - kBottom, H = 0.1;
  for (const double U : {0.1, 0.4}) {
    const double total = bedPressureDrop(U);
    // Gas weight between the first cell centre and the outlet (as in the empty column)
    const double hydrostatic = gas::density(gas::p_out) * gas::g * (H - kCell / 2);
    const double bed = total - hydrostatic;
    const double ergun = ergunPerLength(U, eps, gas::density(gas::p_out + total)) * L;
    EXPECT_NEAR(bed, ergun, 0.03 * ergun) << "superficial velocity " << U << " m/s";
    std::printf("U = %.2f m/s: bed pressure drop %.4f Pa, Ergun %.4f Pa (%.3f %%)\n", U, bed, ergun,
                100 * (bed - ergun) / ergun);
  }
}

}  // namespace
}  // namespace cosim::test
