// The progress line: simulated time, wall time, steps per second, ETA. Rates and ETA are those
// of the last 30 s of wall time (RecentRate), so a slow first step does not inflate the ETA.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>

#include "recent_rate.h"

namespace cosim::orchestrator {

class Progress {
 public:
  // Wall clock in seconds (any origin); the default is std::chrono::steady_clock. Tests give a
  // synthetic one, and a stream to print to instead of stdout.
  using WallClock = std::function<double()>;

  // t0: where this piece starts (a resumed run: its checkpoint's time); t1: the run's end. The
  // percentage shown is of the run from `origin` (its coupling.start_time; t0 when not given) to
  // t1, so a resumed run at t = 20 of 40 s shows 50 %; rates, ETA and the log cadence are of
  // this piece.
  Progress(double t0, double t1, bool quiet, WallClock clock = {}, std::FILE* out = stdout,
           std::optional<double> origin = std::nullopt);
  void update(double t, std::uint64_t steps, std::size_t particles);
  void finish(double t, std::uint64_t steps);
  void abort();

 private:
  void print(double t, std::uint64_t steps, std::size_t particles, bool final);
  double t0_, t1_, origin_;
  bool quiet_;
  WallClock clock_;
  std::FILE* out_;
  bool tty_;
  bool open_line_ = false;
  double start_, last_;
  double last_fraction_ = -1.0;
  RecentRate time_rate_, step_rate_;
};

}  // namespace cosim::orchestrator
