#include "progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace cosim::orchestrator {

using Clock = std::chrono::steady_clock;

namespace {
std::string duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) return fmt::format("{:.0f} s", s);
  const int whole = static_cast<int>(s);
  if (s < 3600) return fmt::format("{} min {:02d} s", whole / 60, whole % 60);
  return fmt::format("{} h {:02d} min", whole / 3600, (whole % 3600) / 60);
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
  fmt::print(
      "{}t = {:.4g} / {:.4g} s ({:5.1f}%)  step {}  {} particles  wall {}  {:.1f} steps/s  ETA "
      "{}{}",
      tty_ ? "\r\033[K" : "", t, t1_, 100.0 * frac, steps, particles, duration(wall), rate,
      final ? "0 s" : duration(eta), tty_ && !final ? "" : "\n");
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
  fmt::print("cosim: reached t = {:.6g} s in {} coupling steps, wall {}\n", t, steps,
             duration(wall));
  open_line_ = false;
}

void Progress::abort() {
  if (open_line_) std::printf("\n");
  open_line_ = false;
  std::fflush(stdout);
}

}  // namespace cosim::orchestrator
