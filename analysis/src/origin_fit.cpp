#include "cosim/analysis/origin_fit.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace cosim::analysis {

OriginFit fitThroughOrigin(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size())
    throw std::invalid_argument("fitThroughOrigin: x and y differ in length");
  if (x.empty()) throw std::invalid_argument("fitThroughOrigin: no points");
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  if (!(sxx > 0)) throw std::invalid_argument("fitThroughOrigin: all x are zero");
  OriginFit f;
  f.slope = sxy / sxx;
  f.residuals.resize(x.size());
  double ss = 0, hc3 = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - f.slope * x[i];
    f.residuals[i] = r;
    ss += r * r;
    const double h = x[i] * x[i] / sxx;
    const double lever = 1.0 - h;
    hc3 +=
        lever > 0 ? x[i] * x[i] * r * r / (lever * lever) : std::numeric_limits<double>::infinity();
  }
  const double n = static_cast<double>(x.size());
  f.rms_residual = std::sqrt(ss / n);
  if (x.size() < 2) {
    f.se_classic = f.se_robust = std::numeric_limits<double>::quiet_NaN();
  } else {
    f.se_classic = std::sqrt(ss / (n - 1.0) / sxx);
    f.se_robust = std::sqrt(hc3) / sxx;
  }
  return f;
}

}  // namespace cosim::analysis
