#include "cosim/analysis/histogram.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cosim::analysis {

double quantileSorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) throw std::invalid_argument("quantile of an empty sample");
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(pos));
  if (i + 1 >= sorted.size()) return sorted.back();
  const double f = pos - static_cast<double>(i);
  return sorted[i] + f * (sorted[i + 1] - sorted[i]);
}

Histogram histogram(const std::vector<double>& values, std::size_t bins, std::size_t max_bins) {
  Histogram h;
  if (values.empty()) {
    h.rule = "empty";
    return h;
  }
  std::vector<double> s = values;
  std::sort(s.begin(), s.end());
  const double lo = s.front();
  const double hi = s.back();
  const double n = static_cast<double>(s.size());
  if (!(hi > lo)) {
    const double w = lo != 0 ? std::abs(lo) * 1e-6 : 1e-30;
    h.edges = {lo - w, lo + w};
    h.counts = {s.size()};
    h.rule = "single-value";
    return h;
  }
  if (bins > 0) {
    h.rule = "given";
  } else {
    const double iqr = quantileSorted(s, 0.75) - quantileSorted(s, 0.25);
    if (iqr > 0 && s.size() >= 4) {
      const double width = 2.0 * iqr * std::pow(n, -1.0 / 3.0);
      bins = static_cast<std::size_t>(std::ceil((hi - lo) / width));
      h.rule = "freedman-diaconis";
    } else {
      bins = static_cast<std::size_t>(std::ceil(std::log2(n))) + 1;
      h.rule = "sturges";
    }
    bins = std::clamp<std::size_t>(bins, 1, std::max<std::size_t>(max_bins, 1));
  }
  h.edges.resize(bins + 1);
  for (std::size_t i = 0; i <= bins; ++i) {
    h.edges[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(bins);
  }
  h.edges.back() = hi;
  h.counts.assign(bins, 0);
  const double scale = static_cast<double>(bins) / (hi - lo);
  for (double x : s) {
    auto i = static_cast<std::size_t>((x - lo) * scale);
    if (i >= bins) i = bins - 1;
    // Guard the floating division against landing one bin off at an edge.
    while (i > 0 && x < h.edges[i]) --i;
    while (i + 1 < bins && x >= h.edges[i + 1]) ++i;
    ++h.counts[i];
  }
  return h;
}

}  // namespace cosim::analysis
