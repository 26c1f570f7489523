// Least squares of y = b x through the origin.
//   b = sum(x y) / sum(x^2),   r_i = y_i - b x_i
//   classic standard error (constant noise):  se = sqrt( sum(r^2)/(n-1) / sum(x^2) )
//   robust HC3 standard error (noise may grow with x, as coating noise does with t):
//     h_i = x_i^2 / sum(x^2),  se = sqrt( sum( x_i^2 r_i^2 / (1-h_i)^2 ) ) / sum(x^2)
#pragma once

#include <vector>

namespace cosim::analysis {

struct OriginFit {
  double slope = 0;
  double se_classic = 0;  // NaN when n < 2
  double se_robust = 0;   // HC3; NaN when n < 2
  std::vector<double> residuals;
  double rms_residual = 0;  // sqrt(mean(r^2))
};

// Throws std::invalid_argument when sizes differ, n = 0 or sum(x^2) = 0.
OriginFit fitThroughOrigin(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace cosim::analysis
