#include "cosim/models/coupling_terms.h"

#include "cosim/link/fields.h"

namespace cosim::models {

namespace {
const double* ptr(const link::ParticleData& d, const char* name) {
  return d.has(name) ? d.get(name).data() : nullptr;
}
}  // namespace

CouplingTerms evaluateTerms(const SceneModels& m, bool coating, const SceneConstants& c,
                            const link::ParticleData& state, const link::ParticleData& samples,
                            const std::vector<char>& lost, double dt) {
  CouplingTerms t;
  const std::size_t n = state.size();
  t.forcing.ids = state.ids;
  t.exchange.ids = state.ids;

  // The particle state (position, velocity, radius) and the fluid samples (the rest).
  ParcelBatch b = bindParcelBatch(
      n, [&](const char* name) { return state.has(name) ? ptr(state, name) : ptr(samples, name); });
  b.lost = lost.empty() ? nullptr : lost.data();

  if (m.drag) {
    auto& K = t.forcing.field(field::drag_coefficient);
    // the part of each parcel's past force its cell's gas has answered (transient estimate)
    std::vector<double> built_up;
    if (m.wake) {
      built_up = m.wake->startInterval(state.ids, b, c);
      b.built_up_force = built_up.data();
    }
    m.drag->coefficients(b, c, K.data());
    for (std::size_t i = 0; i < n; ++i) {
      if (lost[i]) K[i] = 0.0;
    }
    if (m.wake) m.wake->recordInterval(state.ids, b, K.data(), dt);
    t.forcing.field(field::fluid_velocity) = samples.get(field::fluid_velocity);
    t.exchange.field(field::drag_coefficient) = K;
  }
  if (!m.forces.empty()) {
    auto& F = t.forcing.field(field::explicit_force);
    for (const auto& f : m.forces) f->addForces(b, c, F.data());
    for (std::size_t i = 0; i < n; ++i) {
      if (lost[i]) F[3 * i] = F[3 * i + 1] = F[3 * i + 2] = 0.0;
    }
  }
  if (coating) {
    auto& k = t.exchange.field(field::transfer_coefficient);
    m.mass_transfer->transferCoefficients(b, c, k.data());
    if (m.zone) {
      std::vector<double> inside(n);
      m.zone->mask(b, inside.data());
      for (std::size_t i = 0; i < n; ++i) k[i] *= inside[i];
      t.in_zone.resize(n);
      for (std::size_t i = 0; i < n; ++i) t.in_zone[i] = inside[i] != 0.0 && !lost[i] ? 1 : 0;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (lost[i]) k[i] = 0.0;
    }
  }
  return t;
}

}  // namespace cosim::models
