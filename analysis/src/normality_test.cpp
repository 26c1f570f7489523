#include "cosim/analysis/normality_test.h"

#include <cmath>

namespace cosim::analysis {

namespace {
// D'Agostino (1970): skewness g1 -> standard normal score.
double skewnessScore(double g1, double n) {
  const double y = g1 * std::sqrt((n + 1.0) * (n + 3.0) / (6.0 * (n - 2.0)));
  const double beta2 = 3.0 * (n * n + 27.0 * n - 70.0) * (n + 1.0) * (n + 3.0) /
                       ((n - 2.0) * (n + 5.0) * (n + 7.0) * (n + 9.0));
  const double w2 = -1.0 + std::sqrt(2.0 * (beta2 - 1.0));
  const double delta = 1.0 / std::sqrt(0.5 * std::log(w2));
  const double alpha = std::sqrt(2.0 / (w2 - 1.0));
  const double ya = (y == 0.0 ? 1.0 : y) / alpha;
  return delta * std::log(ya + std::sqrt(ya * ya + 1.0));
}

// Anscombe & Glynn (1983): kurtosis b2 -> standard normal score.
double kurtosisScore(double b2, double n) {
  const double e = 3.0 * (n - 1.0) / (n + 1.0);
  const double var =
      24.0 * n * (n - 2.0) * (n - 3.0) / ((n + 1.0) * (n + 1.0) * (n + 3.0) * (n + 5.0));
  const double x = (b2 - e) / std::sqrt(var);
  const double sqrt_beta1 = 6.0 * (n * n - 5.0 * n + 2.0) / ((n + 7.0) * (n + 9.0)) *
                            std::sqrt(6.0 * (n + 3.0) * (n + 5.0) / (n * (n - 2.0) * (n - 3.0)));
  const double a = 6.0 + 8.0 / sqrt_beta1 *
                             (2.0 / sqrt_beta1 + std::sqrt(1.0 + 4.0 / (sqrt_beta1 * sqrt_beta1)));
  const double term1 = 1.0 - 2.0 / (9.0 * a);
  const double denom = 1.0 + x * std::sqrt(2.0 / (a - 4.0));
  const double term2 = (denom < 0 ? -1.0 : 1.0) * std::cbrt((1.0 - 2.0 / a) / std::abs(denom));
  return (term1 - term2) / std::sqrt(2.0 / (9.0 * a));
}
}  // namespace

NormalityTest dagostinoPearson(const std::vector<double>& v) {
  NormalityTest t;
  t.n = v.size();
  if (t.n < 20) {
    t.problem =
        "normality not tested: " + std::to_string(t.n) + " parcels, the test needs at least 20";
    return t;
  }
  const double n = static_cast<double>(t.n);
  double mean = 0;
  for (double x : v) mean += x;
  mean /= n;
  double m2 = 0, m3 = 0, m4 = 0;
  for (double x : v) {
    const double d = x - mean;
    m2 += d * d;
    m3 += d * d * d;
    m4 += d * d * d * d;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  if (!(m2 > 0)) {
    t.problem = "normality not tested: every parcel has the same coating mass";
    return t;
  }
  t.skewness = m3 / std::pow(m2, 1.5);
  t.kurtosis = m4 / (m2 * m2);
  t.z_skewness = skewnessScore(t.skewness, n);
  t.z_kurtosis = kurtosisScore(t.kurtosis, n);
  t.k2 = t.z_skewness * t.z_skewness + t.z_kurtosis * t.z_kurtosis;
  t.p_value = std::exp(-0.5 * t.k2);
  t.valid = true;
  return t;
}

}  // namespace cosim::analysis
