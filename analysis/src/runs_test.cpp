#include "cosim/analysis/runs_test.h"

#include <cmath>

namespace cosim::analysis {

double normalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

RunsTest runsTest(const std::vector<double>& residuals) {
  RunsTest t;
  int last = 0;
  for (double r : residuals) {
    if (r == 0.0 || !std::isfinite(r)) continue;
    const int sign = r > 0 ? 1 : -1;
    (sign > 0 ? t.positive : t.negative) += 1;
    if (sign != last) ++t.runs;
    last = sign;
  }
  if (t.positive == 0 || t.negative == 0) {
    // All of one sign: a single run; no variance under the null, report it as maximal structure
    // only if there are enough residuals to tell.
    t.valid = false;
    return t;
  }
  const double np = static_cast<double>(t.positive), nn = static_cast<double>(t.negative);
  const double n = np + nn;
  t.expected_runs = 2.0 * np * nn / n + 1.0;
  const double var = 2.0 * np * nn * (2.0 * np * nn - n) / (n * n * (n - 1.0));
  if (!(var > 0)) return t;
  t.z = (static_cast<double>(t.runs) - t.expected_runs) / std::sqrt(var);
  t.p_too_few = normalCdf(t.z);
  t.valid = true;
  return t;
}

}  // namespace cosim::analysis
