// Wald-Wolfowitz runs test on the signs of fit residuals: too few runs (long stretches of one
// sign) means the residuals are structured, i.e. the model's shape is wrong. Zero residuals are
// dropped. Normal approximation:
//   mean R = 2 n+ n- / n + 1,  var R = 2 n+ n- (2 n+ n- - n) / (n^2 (n - 1))
//   z = (R - mean) / sqrt(var),  p (too few runs) = Phi(z)
#pragma once

#include <cstddef>
#include <vector>

namespace cosim::analysis {

struct RunsTest {
  bool valid = false;  // needs at least one residual of each sign
  std::size_t positive = 0, negative = 0, runs = 0;
  double expected_runs = 0;
  double z = 0;
  double p_too_few = 1;  // one-sided p-value for "fewer runs than chance"
};

RunsTest runsTest(const std::vector<double>& residuals);

// Standard normal cumulative distribution function.
double normalCdf(double z);

}  // namespace cosim::analysis
