#include "cosim/analysis/coating_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cosim::analysis {

CoatingStatistics coatingStatistics(double time, const std::vector<double>& m,
                                    double uncoated_relative) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  CoatingStatistics s;
  s.time = time;
  s.count = m.size();
  if (m.empty()) {
    s.mean = s.std_dev = s.variance = s.cv = s.min = s.max = s.skewness = s.excess_kurtosis = nan;
    s.uncoated_share = nan;
    return s;
  }
  const double n = static_cast<double>(m.size());
  // Two passes (mean, then central moments) keep round-off small for tightly clustered data.
  double sum = 0;
  for (double x : m) sum += x;
  s.total = sum;
  s.mean = sum / n;
  double m2 = 0, m3 = 0, m4 = 0;
  for (double x : m) {
    const double d = x - s.mean;
    const double d2 = d * d;
    m2 += d2;
    m3 += d2 * d;
    m4 += d2 * d2;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  s.variance = m2;
  s.std_dev = std::sqrt(m2);
  s.cv = s.mean > 0 ? s.std_dev / s.mean : nan;
  s.skewness = m2 > 0 ? m3 / std::pow(m2, 1.5) : nan;
  s.excess_kurtosis = m2 > 0 ? m4 / (m2 * m2) - 3.0 : nan;
  const auto [lo, hi] = std::minmax_element(m.begin(), m.end());
  s.min = *lo;
  s.max = *hi;
  s.uncoated_threshold = s.mean > 0 ? uncoated_relative * s.mean : 0.0;
  std::size_t uncoated = 0;
  for (double x : m) uncoated += x <= s.uncoated_threshold ? 1 : 0;
  s.uncoated_share = static_cast<double>(uncoated) / n;
  return s;
}

}  // namespace cosim::analysis
