#include "cosim/analysis/window_study.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cosim/analysis/growth_fit.h"

namespace cosim::analysis {

namespace {
// Linear interpolation of y(x) at xq over increasing x; clamps outside.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (xq <= x.front()) return y.front();
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (xq <= x[i]) {
      const double f = x[i] > x[i - 1] ? (xq - x[i - 1]) / (x[i] - x[i - 1]) : 1.0;
      return y[i - 1] + f * (y[i] - y[i - 1]);
    }
  }
  return y.back();
}
}  // namespace

WindowStudy studyFitWindow(const std::vector<CoatingStatistics>& snapshots, double t0,
                           double coating_start, double horizon, const TimeSeries* wall) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  WindowStudy w;
  w.horizon = horizon;
  if (snapshots.empty()) return w;
  const auto& last = snapshots.back();
  w.run_end = last.time;
  w.simulated_cv_run_end = last.cv;
  const bool haveWall = wall != nullptr && wall->has(column::wall_seconds) && wall->rows() > 0;
  std::size_t fittedBefore = 0;
  for (int k = 2; k <= 10; ++k) {
    WindowStudyPoint p;
    const double nominal = k == 10 ? w.run_end : t0 + 0.1 * k * (w.run_end - t0);
    const double slack =
        1e-9 * std::max(1.0, std::abs(nominal));  // a snapshot at the window end is in
    const GrowthFit f = fitGrowth(snapshots, t0, nominal + slack, coating_start);
    // A window holding the same snapshots as the previous one repeats it.
    if (!w.points.empty() && f.tau.size() == fittedBefore) continue;
    fittedBefore = f.tau.size();
    p.ok = f.ok;
    p.t_end = f.ok ? f.time.back() : nominal;  // the last snapshot the fit used
    p.wall_seconds =
        haveWall ? interpolate(wall->at(column::time), wall->at(column::wall_seconds), p.t_end)
                 : nan;
    if (f.ok) {
      p.a1 = f.a1;
      p.a1_se = f.a1_se;
      p.a2 = f.a2;
      p.a2_se = f.a2_se;
      p.cv_horizon = (f.a2 / f.a1) / std::sqrt(horizon);
      const double tau = w.run_end - coating_start;
      p.cv_run_end = tau > 0 ? (f.a2 / f.a1) / std::sqrt(tau) : nan;
      // A prediction only for windows that end before the run does.
      p.cv_run_end_error =
          p.t_end < w.run_end && last.cv > 0 ? (p.cv_run_end - last.cv) / last.cv : nan;
    }
    w.points.push_back(p);
  }
  return w;
}

}  // namespace cosim::analysis
