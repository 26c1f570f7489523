// Fit of the paper's Eqs. 9-10 over a window [t0, t1] of snapshots:
//   mu(t) = a1 t          -> least squares through the origin of the snapshot means
//   sigma(t) = a2 sqrt(t) -> variance = a2^2 t, least squares through the origin of the
//                            snapshot variances; a2 = sqrt(slope), se(a2) = se(slope) / (2 a2)
// t is measured from the start of coating (coating_start). Standard errors are the robust HC3
// ones (origin_fit.h), the classic ones are kept for comparison with the paper's figures.
#pragma once

#include <string>
#include <vector>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/origin_fit.h"

namespace cosim::analysis {

struct GrowthFit {
  bool ok = false;
  std::string problem;  // why no fit, when !ok
  double t0 = 0, t1 = 0, coating_start = 0;
  std::vector<double> time;      // snapshot times used [s] (absolute)
  std::vector<double> tau;       // time - coating_start [s]
  std::vector<double> mean;      // [kg]
  std::vector<double> variance;  // [kg^2]
  OriginFit mean_fit;            // slope = a1
  OriginFit variance_fit;        // slope = a2^2
  double a1 = 0, a1_se = 0;      // [kg/s]
  double a2 = 0, a2_se = 0;      // [kg/s^0.5]
  double a1_se_classic = 0, a2_se_classic = 0;
  // RMS residual relative to the mean of the fitted data (scale-free size of the misfit).
  double mean_relative_rms = 0;
  double variance_relative_rms = 0;
};

// Uses the snapshots with t0 <= time <= t1 and time > coating_start; needs at least 3.
GrowthFit fitGrowth(const std::vector<CoatingStatistics>& snapshots, double t0, double t1,
                    double coating_start = 0);

}  // namespace cosim::analysis
