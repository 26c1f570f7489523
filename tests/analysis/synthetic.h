// Synthetic coating data with known answers for the analytics tests.
#pragma once

#include <cmath>
#include <random>
#include <vector>

namespace cosim::analysis::test {

// n parcels drawn independently from N(a1 t, a2^2 t).
inline std::vector<double> normalCoating(std::mt19937_64& rng, std::size_t n, double a1, double a2,
                                         double t) {
  std::normal_distribution<double> d(a1 * t, a2 * std::sqrt(t));
  std::vector<double> m(n);
  for (auto& x : m) x = d(rng);
  return m;
}

// A well-mixed bed followed over time: every parcel gains N(a1 dt, a2^2 dt) per interval, so
// at time t its coating is N(a1 t, a2^2 t) (the Brownian picture behind Eqs. 9-10).
// Returns masses[snapshot][parcel] at t = dt, 2 dt, ..., steps dt.
inline std::vector<std::vector<double>> trackedCoating(std::mt19937_64& rng, std::size_t n,
                                                       double a1, double a2, double dt,
                                                       std::size_t steps,
                                                       double uncoated_share = 0) {
  std::normal_distribution<double> inc(a1 * dt, a2 * std::sqrt(dt));
  const auto never = static_cast<std::size_t>(uncoated_share * static_cast<double>(n));
  // Poor mixing: the first `never` parcels never reach the coating zone; the others take the
  // whole coating, so the bed's mean still grows as a1 t.
  const double boost = n > never ? static_cast<double>(n) / static_cast<double>(n - never) : 1.0;
  std::normal_distribution<double> incPoor(a1 * boost * dt, a2 * std::sqrt(dt));
  std::vector<std::vector<double>> out;
  std::vector<double> m(n, 0.0);
  for (std::size_t s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < n; ++i) {
      if (i < never) continue;
      m[i] += never > 0 ? incPoor(rng) : inc(rng);
    }
    out.push_back(m);
  }
  return out;
}

// Mann's cycle-time picture of a well-mixed bed: each parcel enters the coating zone as a Poisson
// process of `rate` passes per second and takes an exponential deposit of mean w per pass, so its
// coating at time t is a compound Poisson sum with mean rate w t, variance 2 rate w^2 t, skewness
// 3 / sqrt(2 rate t) and excess kurtosis 6 / (rate t). With `slow_share` of the parcels passing
// at `slow_rate` instead (a dead zone that some parcels rarely leave), the bed is not well mixed.
// Returns masses[snapshot][parcel] at t = dt, 2 dt, ..., steps dt.
inline std::vector<std::vector<double>> passCoating(std::mt19937_64& rng, std::size_t n,
                                                    double rate, double w, double dt,
                                                    std::size_t steps, double slow_share = 0,
                                                    double slow_rate = 0) {
  const auto slow = static_cast<std::size_t>(slow_share * static_cast<double>(n));
  std::poisson_distribution<int> passes(rate * dt), slowPasses(slow_rate * dt);
  std::exponential_distribution<double> deposit(1.0 / w);
  std::vector<std::vector<double>> out;
  std::vector<double> m(n, 0.0);
  for (std::size_t s = 0; s < steps; ++s) {
    for (std::size_t i = 0; i < n; ++i) {
      const int k = i < slow ? slowPasses(rng) : passes(rng);
      for (int j = 0; j < k; ++j) m[i] += deposit(rng);
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace cosim::analysis::test
