#include "recent_rate.h"

#include <cmath>

namespace cosim::orchestrator {

void RecentRate::add(double wall, double t) {
  samples_.push_back({wall, t});
  // Keep one sample at or before the window's start, so that the window is always covered.
  while (samples_.size() > 2 && samples_[1].wall <= wall - window_) samples_.pop_front();
}

double RecentRate::rate() const {
  if (samples_.size() < 2) return NAN;
  const Sample& a = samples_.front();
  const Sample& b = samples_.back();
  if (!(b.wall > a.wall)) return NAN;
  return (b.t - a.t) / (b.wall - a.wall);
}

double RecentRate::eta(double t_end) const {
  const double r = rate();
  if (!(r > 0)) return NAN;
  const double left = t_end - samples_.back().t;
  return left > 0 ? left / r : 0.0;
}

}  // namespace cosim::orchestrator
