// Build-up in time of a parcel's own disturbance: see cosim/models/drag/wake_buildup.h and
// docs/models.md ("Build-up in time").
#include "cosim/models/drag/wake_buildup.h"

#include <cmath>

#include "cosim/models/parcel_state.h"

namespace cosim::models {

// 1 - S(tau) = sum w_i exp(-lambda_i tau), printed by scenarios/verify-wake/kernel.py (fit to
// C(tau) / C(inf) over tau in [0, 1e7]; sum w_i = 1, sum w_i lambda_i = 1 / C(inf)).
const std::array<WakeKernel::Mode, WakeKernel::kModes>& WakeKernel::modes() {
  static const std::array<Mode, kModes> m = {{
      {12, 0.05759174590746844},
      {5.5699066003353348, 0.47127798563910717},
      {2.5853216280382609, 0.17861890554853685},
      {1.2000000000000002, 0.10989035152688645},
      {0.55699066003353348, 0.056224920079213862},
      {0.25853216280382596, 0.042915637713834588},
      {0.12, 0.026111078935457419},
      {0.055699066003353323, 0.018479752980988588},
      {0.025853216280382611, 0.012563608148065014},
      {0.012, 0.0081214038328018111},
      {0.005569906600335333, 0.0061377570475202444},
      {0.0025853216280382614, 0.0034891533711843316},
      {0.0012000000000000001, 0.0030952878317478537},
      {0.00055699066003353384, 0.0013989453673044407},
      {0.00025853216280382588, 0.0016138586704714968},
      {0.00012000000000000002, 0.00054891874714744083},
      {5.5699066003353387e-05, 0.00071918125054618357},
      {2.5853216280382585e-05, 0.00045968266001392713},
      {5.5699066003353387e-06, 0.00047087613675032917},
      {2.5853216280382585e-06, 3.8249783970350883e-05},
      {2.5853216280382588e-07, 0.00023269861038862646},
  }};
  return m;
}

double WakeKernel::buildup(double tau) {
  double rest = 0.0;
  for (const auto& m : modes()) rest += m.weight * std::exp(-m.lambda * tau);
  return 1.0 - rest;
}

double WakeKernel::buildupImplicit(int m, double tau_s) {
  double rest = 0.0;
  for (const auto& mode : modes()) rest += mode.weight * std::pow(1.0 + mode.lambda * tau_s, -m);
  return 1.0 - rest;
}

namespace {
// y_i <- (y_i + r_i dt w~_i F) / (1 + r_i dt) over one interval (see the header)
void advanceModes(WakeBuildup::Parcel& s, const double* F, const double* u, double eps, double mu,
                  double rho, double Delta, double dt) {
  const auto& modes = WakeKernel::modes();
  const double nu = 0.5 * (1.0 + eps) * mu / (eps * rho);
  const double viscous = nu / (Delta * Delta);  // [1/s]
  // the flow carries the disturbance away (see the header): c nu / Delta^2, c = (sqrt(1 + Re) -
  // 1)^2, Re = |u| Delta / nu: |u|^2 / (4 nu) at low Re, -> |u| / Delta at high Re
  const double Re = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * Delta / nu;
  const double root = std::sqrt(1.0 + Re) - 1.0;
  const double sweep = viscous * root * root;  // [1/s]
  double norm = 0.0;
  for (const auto& m : modes) norm += m.weight * m.lambda * viscous / (m.lambda * viscous + sweep);
  for (std::size_t k = 0; k < WakeKernel::kModes; ++k) {
    const double r = modes[k].lambda * viscous + sweep;
    const double target = modes[k].weight * (modes[k].lambda * viscous / r) / norm;
    for (int j = 0; j < 3; ++j) {
      double& y = s.y[3 * k + j];
      y = (y + r * dt * target * F[j]) / (1.0 + r * dt);
    }
  }
}
}  // namespace

std::vector<double> WakeBuildup::startInterval(const std::vector<std::int64_t>& ids,
                                               const ParcelBatch& p, const SceneConstants& c) {
  std::vector<double> H(3 * p.n, 0.0);
  State kept;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.isLost(i)) continue;  // in no cell: no disturbance of its own, history dropped
    const double* x = p.position + 3 * i;
    auto it = parcels_.find(ids[i]);
    if (it == parcels_.end()) {  // new: its gas has not felt it yet
      Parcel fresh;
      for (int j = 0; j < 3; ++j) fresh.anchor[j] = x[j];
      kept.emplace(ids[i], fresh);
      continue;
    }
    Parcel s = it->second;
    const double Delta = p.cell_size[i];
    if (s.dt > 0.0) {  // the last interval, with the force the gas got: K (u_f,new - v)
      const double* u = p.fluid_velocity + 3 * i;
      const double F[3] = {s.K * (u[0] - s.v[0]), s.K * (u[1] - s.v[1]), s.K * (u[2] - s.v[2])};
      advanceModes(s, F, u, clampVoidage(p.voidage[i], c), p.fluid_viscosity[i], p.fluid_density[i],
                   Delta, s.dt);
      s.dt = 0.0;
    }
    int steps = 0;
    for (int j = 0; j < 3; ++j) {
      const double cells = std::round((x[j] - s.anchor[j]) / Delta);
      s.anchor[j] += cells * Delta;
      steps += static_cast<int>(std::abs(cells));
    }
    for (std::size_t k = 0; k < WakeKernel::kModes; ++k) {
      const double share = steps == 0 ? 1.0 : std::pow(WakeKernel::neighbourShare(k), steps);
      for (int j = 0; j < 3; ++j) {
        s.y[3 * k + j] *= share;
        H[3 * i + j] += s.y[3 * k + j];
      }
    }
    kept.emplace(ids[i], s);
  }
  parcels_ = std::move(kept);
  return H;
}

void WakeBuildup::recordInterval(const std::vector<std::int64_t>& ids, const ParcelBatch& p,
                                 const double* K, double dt) {
  for (std::size_t i = 0; i < p.n; ++i) {
    auto it = parcels_.find(ids[i]);
    if (p.isLost(i) || it == parcels_.end()) continue;
    Parcel& s = it->second;
    s.K = K[i];
    for (int j = 0; j < 3; ++j) s.v[j] = p.velocity[3 * i + j];
    s.dt = dt;
  }
}

}  // namespace cosim::models
