#include "cosim/analysis/extrapolation.h"

#include <algorithm>
#include <cmath>

namespace cosim::analysis {

CvPrediction predictCv(const GrowthFit& fit, double tau_end, std::size_t points, double band) {
  CvPrediction p;
  p.band = band;
  if (!fit.ok || points < 2) return p;
  const double start = std::max(*std::min_element(fit.tau.begin(), fit.tau.end()), 1e-9);
  const double end = std::max(tau_end, start * 1.0001);
  const double ratio = fit.a2 / fit.a1;
  for (std::size_t i = 0; i < points; ++i) {
    const double f = static_cast<double>(i) / static_cast<double>(points - 1);
    const double tau = start * std::pow(end / start, f);
    const double cv = ratio / std::sqrt(tau);
    p.tau.push_back(tau);
    p.cv.push_back(cv);
    p.cv_low.push_back((1.0 - band) * cv);
    p.cv_high.push_back((1.0 + band) * cv);
  }
  return p;
}

PredictedDistribution predictDistribution(const GrowthFit& fit, double tau, double band) {
  PredictedDistribution d;
  d.tau = tau;
  d.mean = fit.a1 * tau;
  d.sigma = fit.a2 * std::sqrt(tau);
  d.cv = d.mean > 0 ? d.sigma / d.mean : 0.0;
  d.sigma_low = (1.0 - band) * d.sigma;
  d.sigma_high = (1.0 + band) * d.sigma;
  return d;
}

PredictionCheck checkPrediction(const GrowthFit& fit,
                                const std::vector<CoatingStatistics>& snapshots) {
  PredictionCheck c;
  if (!fit.ok) return c;
  auto rel = [](double pred, double sim) { return sim != 0 ? (pred - sim) / sim : std::nan(""); };
  for (const auto& s : snapshots) {
    if (!(s.time > fit.t1) || s.count == 0) continue;
    const double tau = s.time - fit.coating_start;
    PredictionCheckPoint p;
    p.time = s.time;
    p.simulated_mean = s.mean;
    p.predicted_mean = fit.a1 * tau;
    p.mean_error = rel(p.predicted_mean, s.mean);
    p.simulated_std = s.std_dev;
    p.predicted_std = fit.a2 * std::sqrt(tau);
    p.std_error = rel(p.predicted_std, s.std_dev);
    p.simulated_cv = s.cv;
    p.predicted_cv = p.predicted_std / p.predicted_mean;
    p.cv_error = rel(p.predicted_cv, s.cv);
    c.max_abs_mean_error = std::max(c.max_abs_mean_error, std::abs(p.mean_error));
    c.max_abs_std_error = std::max(c.max_abs_std_error, std::abs(p.std_error));
    c.max_abs_cv_error = std::max(c.max_abs_cv_error, std::abs(p.cv_error));
    c.points.push_back(p);
  }
  return c;
}

}  // namespace cosim::analysis
