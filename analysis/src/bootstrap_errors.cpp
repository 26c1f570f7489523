#include "cosim/analysis/bootstrap_errors.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "cosim/analysis/growth_fit.h"

namespace cosim::analysis {

BootstrapErrors bootstrapGrowthErrors(const ParcelHistories& h, double coating_start,
                                      std::size_t resamples, std::uint64_t seed) {
  BootstrapErrors b;
  b.snapshots = h.time.size();
  b.parcels = h.mass.empty() ? 0 : h.mass.front().size();
  if (b.snapshots < 3 || b.parcels < 2 || resamples < 2) {
    b.problem = "bootstrap needs at least 3 snapshots, 2 parcels and 2 resamples";
    return b;
  }
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, b.parcels - 1);
  std::vector<std::size_t> drawn(b.parcels);
  std::vector<CoatingStatistics> stats(b.snapshots);
  double s1 = 0, s11 = 0, s2 = 0, s22 = 0;
  std::size_t good = 0;
  for (std::size_t r = 0; r < resamples; ++r) {
    for (auto& d : drawn) d = pick(rng);
    for (std::size_t s = 0; s < b.snapshots; ++s) {
      const auto& m = h.mass[s];
      double n = 0, sum = 0;
      for (auto d : drawn) {
        if (!std::isnan(m[d])) {
          sum += m[d];
          n += 1;
        }
      }
      double var = 0;
      const double mean = n > 0 ? sum / n : std::nan("");
      for (auto d : drawn) {
        if (!std::isnan(m[d])) var += (m[d] - mean) * (m[d] - mean);
      }
      stats[s].time = h.time[s];
      stats[s].count = static_cast<std::size_t>(n);
      stats[s].mean = mean;
      stats[s].variance = n > 0 ? var / n : std::nan("");
    }
    const GrowthFit f = fitGrowth(stats, h.time.front(), h.time.back(), coating_start);
    if (!f.ok) continue;
    s1 += f.a1;
    s11 += f.a1 * f.a1;
    s2 += f.a2;
    s22 += f.a2 * f.a2;
    ++good;
  }
  b.resamples = good;
  if (good < 2) {
    b.problem = "fewer than 2 resamples could be fitted";
    return b;
  }
  const double g = static_cast<double>(good);
  const double m1 = s1 / g, m2 = s2 / g;
  b.a1_se = std::sqrt(std::max(0.0, (s11 / g - m1 * m1) * g / (g - 1.0)));
  b.a2_se = std::sqrt(std::max(0.0, (s22 / g - m2 * m2) * g / (g - 1.0)));
  b.ok = true;
  return b;
}

}  // namespace cosim::analysis
