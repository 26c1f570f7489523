// Undisturbed gas velocity at a parcel (the parcel's own disturbance removed): see
// cosim/models/drag/undisturbed_velocity.h and docs/models.md.
#include "cosim/models/drag/undisturbed_velocity.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cosim/models/drag/dimensionless_drag.h"
#include "cosim/models/input_checks.h"
#include "cosim/models/parcel_state.h"

namespace cosim::models {

double SelfDisturbance::coupling(double K, double G, double w) {
  // the other parcels of the cell (drag K (1 - w) / w, as much per volume as this one) resist
  // the disturbance in parallel with the free gas: G_eff = 1 / (1/G + K (1 - w) / w)
  const double G_eff = 1.0 / (1.0 / G + K * (1.0 - w) / w);
  return w * K * G_eff;
}

double SelfDisturbance::share(double parcel_radius, double voidage, double Delta) {
  const double solid = (1.0 - voidage) * Delta * Delta * Delta;
  const double parcel = 4.0 / 3.0 * std::numbers::pi * parcel_radius * parcel_radius * parcel_radius;
  if (!(solid > parcel)) return 1.0;  // no other solid in the cell (or round-off): the full correction
  return parcel / solid;
}

UndisturbedVelocityDrag::UndisturbedVelocityDrag(std::unique_ptr<DragLaw> inner)
    : inner_(std::move(inner)) {}

std::vector<std::string> UndisturbedVelocityDrag::requiredFields() const {
  std::vector<std::string> f = inner_->requiredFields();
  for (const char* x : {"radius", "velocity", "fluid_velocity", "voidage", "fluid_density",
                        "fluid_viscosity", "cell_size"}) {
    if (std::find(f.begin(), f.end(), x) == f.end()) f.push_back(x);
  }
  return f;
}

void UndisturbedVelocityDrag::coefficients(const ParcelBatch& p, const SceneConstants& c,
                                           double* K) const {
  const std::string owner = "undisturbed_velocity 'self_disturbance' of " + dragOwner(name());
  validateConstants(owner, c);
  checkInputs(owner, requiredFields(), p, c);

  // Response G of the free gas and share w of every parcel (from the sampled state)
  std::vector<double> G(p.n, 0.0), w(p.n, 1.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) continue;
    const double eps = clampVoidage(p.voidage[i], c);
    const double* u = p.fluid_velocity + 3 * i;
    const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    G[i] = SelfDisturbance::response(eps, p.fluid_viscosity[i], p.fluid_density[i], speed,
                                     p.cell_size[i]);
    w[i] = SelfDisturbance::share(p.radius[i], p.voidage[i], p.cell_size[i]);
  }

  // Fixed point K = K(u_und), u_und - v = (u_s - v) / (1 - a)
  inner_->coefficients(p, c, K);
  std::vector<double> u_und(3 * p.n);
  ParcelBatch q = p;
  q.fluid_velocity = u_und.data();
  auto coupling = [&](std::size_t i) {
    return std::min(SelfDisturbance::coupling(K[i], G[i], w[i]), SelfDisturbance::kMaxSelfCoupling);
  };
  std::vector<double> previous(p.n);
  for (int pass = 1; pass < SelfDisturbance::kMaxPasses; ++pass) {
    for (std::size_t i = 0; i < p.n; ++i) {
      previous[i] = K[i];
      const double amplify = 1.0 / (1.0 - coupling(i));
      for (int j = 0; j < 3; ++j) {
        const double v = p.velocity[3 * i + j];
        u_und[3 * i + j] = v + (p.fluid_velocity[3 * i + j] - v) * amplify;
      }
    }
    inner_->coefficients(q, c, K);
    bool converged = true;
    for (std::size_t i = 0; i < p.n && converged; ++i) {
      converged = std::abs(K[i] - previous[i]) <= SelfDisturbance::kTolerance * std::abs(K[i]);
    }
    if (converged) break;
  }
  for (std::size_t i = 0; i < p.n; ++i) K[i] /= 1.0 - coupling(i);
  checkOutputs(owner, "drag coefficient K", K, p.n);
}

std::vector<std::string> undisturbedVelocityNames() { return {"none", "self_disturbance"}; }

}  // namespace cosim::models
