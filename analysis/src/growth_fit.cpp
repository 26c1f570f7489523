#include "cosim/analysis/growth_fit.h"

#include <cmath>
#include <limits>

namespace cosim::analysis {

GrowthFit fitGrowth(const std::vector<CoatingStatistics>& snapshots, double t0, double t1,
                    double coating_start) {
  GrowthFit g;
  g.t0 = t0;
  g.t1 = t1;
  g.coating_start = coating_start;
  for (const auto& s : snapshots) {
    if (s.time < t0 || s.time > t1 || !(s.time > coating_start) || s.count == 0) continue;
    if (!std::isfinite(s.mean) || !std::isfinite(s.variance)) continue;
    g.time.push_back(s.time);
    g.tau.push_back(s.time - coating_start);
    g.mean.push_back(s.mean);
    g.variance.push_back(s.variance);
  }
  if (g.tau.size() < 3) {
    g.problem = "only " + std::to_string(g.tau.size()) +
                " snapshot(s) with particles in the fit window [" + std::to_string(t0) + ", " +
                std::to_string(t1) +
                "] s after the coating start; at least 3 are needed (widen the window or record "
                "more often)";
    return g;
  }
  g.mean_fit = fitThroughOrigin(g.tau, g.mean);
  g.variance_fit = fitThroughOrigin(g.tau, g.variance);
  g.a1 = g.mean_fit.slope;
  g.a1_se = g.mean_fit.se_robust;
  g.a1_se_classic = g.mean_fit.se_classic;
  const double b = g.variance_fit.slope;
  if (!(g.a1 > 0)) {
    g.problem =
        "the mean coating mass does not grow over the fit window (a1 = " + std::to_string(g.a1) +
        " kg/s): no coating happened; check the coating zone and the precursor feed";
    return g;
  }
  if (!(b > 0)) {
    g.problem = "the variance of the coating mass does not grow over the fit window (slope " +
                std::to_string(b) + " kg^2/s)";
    return g;
  }
  g.a2 = std::sqrt(b);
  g.a2_se = g.variance_fit.se_robust / (2.0 * g.a2);
  g.a2_se_classic = g.variance_fit.se_classic / (2.0 * g.a2);
  double mm = 0, mv = 0;
  for (std::size_t i = 0; i < g.tau.size(); ++i) {
    mm += std::abs(g.mean[i]);
    mv += std::abs(g.variance[i]);
  }
  const double n = static_cast<double>(g.tau.size());
  g.mean_relative_rms =
      mm > 0 ? g.mean_fit.rms_residual / (mm / n) : std::numeric_limits<double>::quiet_NaN();
  g.variance_relative_rms =
      mv > 0 ? g.variance_fit.rms_residual / (mv / n) : std::numeric_limits<double>::quiet_NaN();
  g.ok = true;
  return g;
}

}  // namespace cosim::analysis
