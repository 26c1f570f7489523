// Error against run time: how long must a run be for its extrapolation to be trusted?
// The Eqs. 9-10 fit is repeated on growing windows [t0, t_k] (t_k = t0 + f_k (t_end - t0),
// f_k = 0.2, 0.3, ..., 1.0; a window holding the same snapshots as the previous one is
// skipped). For each window: a1, a2 with standard errors, the CV predicted at
// the horizon (e.g. 20 min), the CV predicted at the end of the run and its error against the
// simulated CV there (for windows shorter than the run), and the wall-clock time the
// simulation needed to reach t_k (from the cumulative wall_seconds of timeseries.csv).
#pragma once

#include <vector>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/time_series.h"

namespace cosim::analysis {

struct WindowStudyPoint {
  double t_end = 0;         // [s] last snapshot in the window (nominal end if no fit)
  double wall_seconds = 0;  // [s] wall time to simulate up to t_end; NaN if unknown
  bool ok = false;          // fit possible
  double a1 = 0, a1_se = 0, a2 = 0, a2_se = 0;
  double cv_horizon = 0;  // CV predicted at the horizon
  double cv_run_end = 0;  // CV predicted at the last snapshot
  double cv_run_end_error =
      0;  // (predicted - simulated) / simulated at the last snapshot; NaN for the full window
};

struct WindowStudy {
  double horizon = 0;  // [s] since coating start
  double run_end = 0;  // [s] time of the last snapshot
  double simulated_cv_run_end = 0;
  std::vector<WindowStudyPoint> points;
};

// wall: a time series with time and wall_seconds columns (may be empty: wall times unknown).
WindowStudy studyFitWindow(const std::vector<CoatingStatistics>& snapshots, double t0,
                           double coating_start, double horizon, const TimeSeries* wall = nullptr);

}  // namespace cosim::analysis
