#include "cosim/models/coupling_terms.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <thread>

#include "cosim/link/fields.h"

namespace cosim::models {

namespace {
const double* ptr(const link::ParticleData& d, const char* name) {
  return d.has(name) ? d.get(name).data() : nullptr;
}

// The laws over parcels [first, first + n) of the state and samples, into the terms' arrays
// (already of full length). A parcel's terms depend on that parcel alone, so any split of the
// parcels gives the same numbers.
struct Part {
  const SceneModels& m;
  bool coating;
  const SceneConstants& c;
  const link::ParticleData& state;
  const link::ParticleData& samples;
  const std::vector<char>& lost;
  double* K = nullptr;      // forcing drag_coefficient
  double* F = nullptr;      // forcing explicit_force
  double* k = nullptr;      // exchange transfer_coefficient
  char* in_zone = nullptr;  // with a zone

  void operator()(std::size_t first, std::size_t n) const {
    ParcelBatch b = bindParcelBatch(n, [&](const char* name) -> const double* {
      const double* base = state.has(name) ? ptr(state, name) : ptr(samples, name);
      return base == nullptr ? nullptr : base + first * field::components(name);
    });
    b.first = first;
    b.lost = lost.empty() ? nullptr : lost.data() + first;
    const char* gone = lost.data() + first;
    if (K != nullptr) {
      double* Kp = K + first;
      m.drag->coefficients(b, c, Kp);
      for (std::size_t i = 0; i < n; ++i) {
        if (gone[i]) Kp[i] = 0.0;
      }
    }
    if (F != nullptr) {
      double* Fp = F + 3 * first;
      for (const auto& f : m.forces) f->addForces(b, c, Fp);
      for (std::size_t i = 0; i < n; ++i) {
        if (gone[i]) Fp[3 * i] = Fp[3 * i + 1] = Fp[3 * i + 2] = 0.0;
      }
    }
    if (k != nullptr) {
      double* kp = k + first;
      m.mass_transfer->transferCoefficients(b, c, kp);
      if (m.zone) {
        std::vector<double> inside(n);
        m.zone->mask(b, inside.data());
        for (std::size_t i = 0; i < n; ++i) kp[i] *= inside[i];
        for (std::size_t i = 0; i < n; ++i)
          in_zone[first + i] = inside[i] != 0.0 && !gone[i] ? 1 : 0;
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (gone[i]) kp[i] = 0.0;
      }
    }
  }
};

// Parts of at least this many parcels: below, a thread costs more than it saves.
constexpr std::size_t kPartParcels = 8192;
}  // namespace

CouplingTerms evaluateTerms(const SceneModels& m, bool coating, const SceneConstants& c,
                            const link::ParticleData& state, const link::ParticleData& samples,
                            const std::vector<char>& lost, double dt, unsigned threads) {
  CouplingTerms t;
  const std::size_t n = state.size();
  t.forcing.ids = state.ids;
  t.exchange.ids = state.ids;

  // The wake's force history is one map of every parcel: over all parcels at once, here
  if (m.drag && m.wake) {
    ParcelBatch b = bindParcelBatch(n, [&](const char* name) {
      return state.has(name) ? ptr(state, name) : ptr(samples, name);
    });
    b.lost = lost.empty() ? nullptr : lost.data();
    auto& K = t.forcing.field(field::drag_coefficient);
    std::vector<double> built_up = m.wake->startInterval(state.ids, b, c);
    b.built_up_force = built_up.data();
    m.drag->coefficients(b, c, K.data());
    for (std::size_t i = 0; i < n; ++i) {
      if (lost[i]) K[i] = 0.0;
    }
    m.wake->recordInterval(state.ids, b, K.data(), dt);
  }
  Part part{m, coating, c, state, samples, lost};
  if (m.drag && !m.wake) part.K = t.forcing.field(field::drag_coefficient).data();
  if (!m.forces.empty()) part.F = t.forcing.field(field::explicit_force).data();
  if (coating) {
    part.k = t.exchange.field(field::transfer_coefficient).data();
    if (m.zone) {
      t.in_zone.resize(n);
      part.in_zone = t.in_zone.data();
    }
  }

  // The parcels in contiguous parts, one a thread; the first on this one
  const std::size_t parts =
      m.splittable ? std::max<std::size_t>(1, std::min<std::size_t>(threads, n / kPartParcels)) : 1;
  if (parts == 1) {
    part(0, n);
  } else {
    std::vector<std::thread> others;
    std::vector<std::exception_ptr> failed(parts);
    const auto bounds = [&](std::size_t j) { return n * j / parts; };
    for (std::size_t j = 1; j < parts; ++j) {
      others.emplace_back([&, j] {
        try {
          part(bounds(j), bounds(j + 1) - bounds(j));
        } catch (...) {
          failed[j] = std::current_exception();
        }
      });
    }
    try {
      part(0, bounds(1));
    } catch (...) {
      failed[0] = std::current_exception();
    }
    for (auto& th : others) th.join();
    for (const auto& e : failed) {  // the first part's error first: the lowest parcel named
      if (e) std::rethrow_exception(e);
    }
  }
  if (m.drag) {
    t.forcing.field(field::fluid_velocity) = samples.get(field::fluid_velocity);
    t.exchange.field(field::drag_coefficient) = t.forcing.get(field::drag_coefficient);
  }
  return t;
}

}  // namespace cosim::models
