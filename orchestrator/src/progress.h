// The progress line: simulated time, wall time, steps per second, ETA.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

namespace cosim::orchestrator {

class Progress {
 public:
  Progress(double t0, double t1, bool quiet);
  void update(double t, std::uint64_t steps, std::size_t particles);
  void finish(double t, std::uint64_t steps);
  void abort();

 private:
  void print(double t, std::uint64_t steps, std::size_t particles, bool final);
  double t0_, t1_;
  bool quiet_, tty_;
  bool open_line_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  double last_fraction_ = -1.0;
};

}  // namespace cosim::orchestrator
