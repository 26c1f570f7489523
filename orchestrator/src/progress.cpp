#include "progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace cosim::orchestrator {

using Clock = std::chrono::steady_clock;

namespace {
void duration(char* buf, std::size_t n, double s) {
  if (!std::isfinite(s) || s < 0) {
    std::snprintf(buf, n, "?");
  } else if (s < 60) {
    std::snprintf(buf, n, "%.0f s", s);
  } else if (s < 3600) {
    std::snprintf(buf, n, "%d min %02d s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  } else {
    std::snprintf(buf, n, "%d h %02d min", static_cast<int>(s) / 3600, (static_cast<int>(s) % 3600) / 60);
  }
}
}  // namespace

Progress::Progress(double t0, double t1, bool quiet)
    : t0_(t0), t1_(t1), quiet_(quiet), tty_(isatty(STDOUT_FILENO) != 0),
      start_(Clock::now()), last_(Clock::now() - std::chrono::hours(1)) {}

void Progress::print(double t, std::uint64_t steps, std::size_t particles, bool final) {
  const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
  const double frac = (t - t0_) / (t1_ - t0_);
  const double rate = wall > 0 ? static_cast<double>(steps) / wall : 0.0;
  const double eta = frac > 0 ? wall * (1.0 - frac) / frac : NAN;
  char w[32], e[32];
  duration(w, sizeof w, wall);
  duration(e, sizeof e, eta);
  std::printf("%st = %.4g / %.4g s (%5.1f%%)  step %llu  %zu particles  wall %s  %.1f steps/s  ETA %s%s",
              tty_ ? "\r\033[K" : "", t, t1_, 100.0 * frac, static_cast<unsigned long long>(steps),
              particles, w, rate, final ? "0 s" : e, tty_ && !final ? "" : "\n");
  std::fflush(stdout);
  open_line_ = tty_ && !final;
}

void Progress::update(double t, std::uint64_t steps, std::size_t particles) {
  if (quiet_) return;
  const auto now = Clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  const double frac = (t - t0_) / (t1_ - t0_);
  // A terminal gets a live line; a log file gets a line every 10 % or every 30 s.
  const bool due = tty_ ? since > 0.25 : (frac - last_fraction_ >= 0.1 || since > 30.0);
  if (!due) return;
  last_ = now;
  last_fraction_ = frac;
  print(t, steps, particles, false);
}

void Progress::finish(double t, std::uint64_t steps) {
  if (quiet_) return;
  if (open_line_) std::printf("\n");
  const double wall = std::chrono::duration<double>(Clock::now() - start_).count();
  char w[32];
  duration(w, sizeof w, wall);
  std::printf("cosim: reached t = %.6g s in %llu coupling steps, wall %s\n", t,
              static_cast<unsigned long long>(steps), w);
  open_line_ = false;
}

void Progress::abort() {
  if (open_line_) std::printf("\n");
  open_line_ = false;
  std::fflush(stdout);
}

}  // namespace cosim::orchestrator
