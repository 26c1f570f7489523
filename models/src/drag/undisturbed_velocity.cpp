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
  const double parcel =
      4.0 / 3.0 * std::numbers::pi * parcel_radius * parcel_radius * parcel_radius;
  if (!(solid > parcel))
    return 1.0;  // no other solid in the cell (or round-off): the full correction
  return parcel / solid;
}

UndisturbedVelocityDrag::UndisturbedVelocityDrag(std::unique_ptr<DragLaw> inner, Estimate estimate,
                                                 double gamma, double beta)
    : inner_(std::move(inner)), estimate_(estimate), gamma_(gamma), beta_(beta) {}

std::vector<std::string> UndisturbedVelocityDrag::requiredFields() const {
  std::vector<std::string> f = inner_->requiredFields();
  for (const char* x : {"radius", "velocity", "fluid_velocity", "voidage", "fluid_density",
                        "fluid_viscosity", "cell_size"}) {
    if (std::find(f.begin(), f.end(), x) == f.end()) f.push_back(x);
  }
  // the transient history follows the parcel from cell to cell
  if (transient() && std::find(f.begin(), f.end(), "position") == f.end()) f.push_back("position");
  return f;
}

void UndisturbedVelocityDrag::coefficients(const ParcelBatch& p, const SceneConstants& c,
                                           double* K) const {
  const std::string owner =
      "undisturbed_velocity '" +
      std::string(transient() ? "self_disturbance_transient" : "self_disturbance") + "' of " +
      dragOwner(name());
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
  if (transient()) {
    transientCoefficients(owner, p, c, G.data(), w.data(), K);
  } else {
    steadyCoefficients(p, c, G.data(), w.data(), K);
  }
  checkOutputs(owner, "drag coefficient K", K, p.n);
}

// Fixed point K = K(u_und), u_und - v = (u_s - v) / (1 + beta f - gamma a)
void UndisturbedVelocityDrag::steadyCoefficients(const ParcelBatch& p, const SceneConstants& c,
                                                 const double* G, const double* w,
                                                 double* K) const {
  inner_->coefficients(p, c, K);
  std::vector<double> u_und(3 * p.n);
  ParcelBatch q = p;
  q.fluid_velocity = u_und.data();
  // 1 + beta f - gamma a, f = a / (K G) (1 for a lone parcel), gamma a capped as a is
  auto denominator = [&](std::size_t i) {
    const double a = SelfDisturbance::coupling(K[i], G[i], w[i]);
    const double f = K[i] * G[i] > 0.0 ? a / (K[i] * G[i]) : 1.0;
    return std::max(1.0 + beta_ * f - std::min(gamma_ * a, SelfDisturbance::kMaxSelfCoupling),
                    CalibrationBounds::kMinDenominator);
  };
  std::vector<double> previous(p.n);
  for (int pass = 1; pass < SelfDisturbance::kMaxPasses; ++pass) {
    for (std::size_t i = 0; i < p.n; ++i) {
      previous[i] = K[i];
      const double amplify = 1.0 / denominator(i);
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
  for (std::size_t i = 0; i < p.n; ++i) K[i] /= denominator(i);
}

// u_und - v = (u_s - v + gamma w G_eff(K) H) / (1 + beta f), K = K(u_und) (fixed point through
// G_eff and f only), then the factor K_eff / K = 1 + x that gives K (u_und - v) along the sampled
// slip.
void UndisturbedVelocityDrag::transientCoefficients(const std::string& owner, const ParcelBatch& p,
                                                    const SceneConstants& c, const double* G,
                                                    const double* w, double* K) const {
  if (p.built_up_force == nullptr) {
    throw ModelError(owner +
                     ": needs the built-up force of every parcel (ParcelBatch::built_up_force), "
                     "which the coupler keeps per parcel id; this caller does not provide it: use "
                     "'self_disturbance' (steady) here");
  }
  inner_->coefficients(p, c, K);
  std::vector<double> u_und(3 * p.n);
  ParcelBatch q = p;
  q.fluid_velocity = u_und.data();
  std::vector<double> previous(p.n);
  for (int pass = 1; pass < SelfDisturbance::kMaxPasses; ++pass) {
    for (std::size_t i = 0; i < p.n; ++i) {
      previous[i] = K[i];
      if (p.isLost(i)) {  // in no cell (G = 0): no disturbance to remove
        for (int j = 0; j < 3; ++j) u_und[3 * i + j] = p.fluid_velocity[3 * i + j];
        continue;
      }
      const double G_eff = 1.0 / (1.0 / G[i] + K[i] * (1.0 - w[i]) / w[i]);
      const double offset = 1.0 + beta_ * G_eff * w[i] / G[i];  // 1 + beta f, f = w G_eff / G
      const double scale = gamma_ * w[i] * G_eff;
      for (int j = 0; j < 3; ++j) {
        const double v = p.velocity[3 * i + j];
        u_und[3 * i + j] =
            v + (p.fluid_velocity[3 * i + j] - v + scale * p.built_up_force[3 * i + j]) / offset;
      }
    }
    inner_->coefficients(q, c, K);
    bool converged = true;
    for (std::size_t i = 0; i < p.n && converged; ++i) {
      converged = std::abs(K[i] - previous[i]) <= SelfDisturbance::kTolerance * std::abs(K[i]);
    }
    if (converged) break;
  }
  for (std::size_t i = 0; i < p.n; ++i) {
    double along = 0.0, slip2 = 0.0;
    for (int j = 0; j < 3; ++j) {
      const double slip = p.fluid_velocity[3 * i + j] - p.velocity[3 * i + j];
      along += (u_und[3 * i + j] - p.fluid_velocity[3 * i + j]) * slip;
      slip2 += slip * slip;
    }
    const double x = slip2 > 0.0 ? along / slip2 : 0.0;
    K[i] *= 1.0 + std::clamp(x, TransientBounds::kMinGain, TransientBounds::kMaxGain);
  }
}

std::vector<std::string> undisturbedVelocityNames() {
  return {"none", "self_disturbance", "self_disturbance_transient"};
}

}  // namespace cosim::models
