// RecentRate: how fast a run advances now, for the progress line's ETA. The rate is that of the
// last `window` seconds of wall time, not the average since the start: the first coupling step
// (solver set-up, first linear solves) can take as long as hundreds of later ones, and an average
// since the start would extrapolate it over the whole run.
#pragma once

#include <deque>

namespace cosim::orchestrator {

class RecentRate {
 public:
  explicit RecentRate(double window_seconds = 30.0) : window_(window_seconds) {}

  // The run reached simulated time `t` at wall time `wall` [s, any origin, non-decreasing].
  // The first sample is the end of the first step: the rate is measured from there on.
  void add(double wall, double t);
  // Simulated seconds per wall second over the window (at least the last two samples); NaN
  // before there are two samples a positive wall time apart.
  double rate() const;
  // Wall seconds until `t_end` at rate(); NaN if the rate is unknown or not positive.
  double eta(double t_end) const;

 private:
  struct Sample {
    double wall, t;
  };
  double window_;
  std::deque<Sample> samples_;
};

}  // namespace cosim::orchestrator
