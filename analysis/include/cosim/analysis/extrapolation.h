// Extrapolation of a well-mixed run with the paper's Eqs. 9-10 (section 2.3, Figs. 11-12):
//   CV(t) = (a2/a1) / sqrt(t), with the band for a2 -> (1 -+ band) a2 (paper: 20 %);
//   the normal distribution N(a1 t, a2^2 t) at chosen times (paper: 5 and 20 min);
//   and, when the run goes past the fit window, the prediction against the later snapshots.
// t is measured from the coating start.
#pragma once

#include <vector>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/growth_fit.h"

namespace cosim::analysis {

struct CvPrediction {
  std::vector<double> tau;  // [s] since coating start
  std::vector<double> cv, cv_low, cv_high;
  double band = 0.2;
};

// points log-spaced from the first fitted tau to tau_end (paper: 60 min).
CvPrediction predictCv(const GrowthFit& fit, double tau_end = 3600.0, std::size_t points = 200,
                       double band = 0.2);

struct PredictedDistribution {
  double tau = 0;    // [s] since coating start
  double mean = 0;   // [kg] a1 tau
  double sigma = 0;  // [kg] a2 sqrt(tau)
  double cv = 0;
  double sigma_low = 0, sigma_high = 0;  // with a2 -+ band
};

PredictedDistribution predictDistribution(const GrowthFit& fit, double tau, double band = 0.2);

struct PredictionCheckPoint {
  double time = 0;                                                // [s] absolute
  double simulated_mean = 0, predicted_mean = 0, mean_error = 0;  // error = (pred - sim) / sim
  double simulated_std = 0, predicted_std = 0, std_error = 0;
  double simulated_cv = 0, predicted_cv = 0, cv_error = 0;
};

struct PredictionCheck {
  std::vector<PredictionCheckPoint> points;  // snapshots after the fit window
  double max_abs_mean_error = 0, max_abs_std_error = 0, max_abs_cv_error = 0;
};

PredictionCheck checkPrediction(const GrowthFit& fit,
                                const std::vector<CoatingStatistics>& snapshots);

}  // namespace cosim::analysis
