// Per-snapshot statistics of the coating mass per parcel: mean, standard deviation, CV (paper
// Eq. 1), share of never-coated parcels, skewness and excess kurtosis.
#pragma once

#include <cstddef>
#include <vector>

namespace cosim::analysis {

struct CoatingStatistics {
  double time = 0;          // [s]
  std::size_t count = 0;    // parcels
  double mean = 0;          // [kg]
  double std_dev = 0;       // [kg] population standard deviation (all parcels are the population)
  double variance = 0;      // [kg^2] std_dev^2
  double cv = 0;            // std_dev / mean; NaN when mean <= 0
  double min = 0, max = 0;  // [kg]
  double total = 0;         // [kg] sum over parcels
  double uncoated_threshold = 0;  // [kg] a parcel at or below this counts as never coated
  double uncoated_share = 0;      // [-] fraction of parcels at or below the threshold
  double skewness = 0;            // g1 = m3 / m2^1.5 (NaN if m2 = 0)
  double excess_kurtosis = 0;     // g2 = m4 / m2^2 - 3 (NaN if m2 = 0)
};

// uncoated_relative: threshold as a fraction of the mean (e.g. 1e-6). With mean <= 0 every
// parcel counts as uncoated. Empty input gives count 0 and NaN moments.
CoatingStatistics coatingStatistics(double time, const std::vector<double>& coating_mass,
                                    double uncoated_relative = 1e-6);

}  // namespace cosim::analysis
