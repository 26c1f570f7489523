// Histogram of coating mass with the Freedman-Diaconis bin rule (width 2 IQR n^(-1/3)),
// falling back to Sturges (ceil(log2 n) + 1 bins) when the IQR is zero or n < 4. The bin count
// is clamped to [1, max_bins]. Bins are [e_i, e_i+1), the last one closed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace cosim::analysis {

struct Histogram {
  std::vector<double> edges;        // bins + 1 increasing edges [kg]
  std::vector<std::size_t> counts;  // bins
  std::string rule;                 // "freedman-diaconis", "sturges", "given" or "single-value"
};

// Quantile with linear interpolation between order statistics (numpy's default, type 7).
// `sorted` must be sorted ascending and non-empty.
double quantileSorted(const std::vector<double>& sorted, double q);

// bins = 0 chooses by the rule above; bins > 0 uses that many equal bins over [min, max].
Histogram histogram(const std::vector<double>& values, std::size_t bins = 0,
                    std::size_t max_bins = 100);

}  // namespace cosim::analysis
