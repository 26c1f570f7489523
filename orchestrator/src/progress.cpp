#include "progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "cosim/util/format.h"

namespace cosim::orchestrator {

namespace {
double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Progress::Progress(double t0, double t1, bool quiet, WallClock clock, std::FILE* out,
                   std::optional<double> origin)
    : t0_(t0),
      t1_(t1),
      origin_(std::min(origin.value_or(t0), t0)),
      quiet_(quiet),
      clock_(clock ? std::move(clock) : WallClock(steadySeconds)),
      out_(out),
      tty_(isatty(fileno(out)) != 0),
      start_(clock_()),
      last_(start_ - 3600.0) {}

void Progress::print(double t, std::uint64_t steps, std::size_t particles, bool final) {
  const double wall = clock_() - start_;
  const double frac = (t - origin_) / (t1_ - origin_);
  const double steps_per_s = step_rate_.rate();
  fmt::print(out_,
             "{}t = {:.4g} / {:.4g} s ({:5.1f}%)  step {}  {} particles  wall {}  {} steps/s  ETA "
             "{}{}",
             tty_ ? "\r\033[K" : "", t, t1_, 100.0 * frac, steps, particles,
             util::clockDuration(wall),
             std::isfinite(steps_per_s) ? fmt::format("{:.1f}", steps_per_s) : std::string("?"),
             final ? "0 s" : util::clockDuration(time_rate_.eta(t1_)), tty_ && !final ? "" : "\n");
  std::fflush(out_);
  open_line_ = tty_ && !final;
}

void Progress::update(double t, std::uint64_t steps, std::size_t particles) {
  if (quiet_) return;
  const double now = clock_();
  time_rate_.add(now, t);
  step_rate_.add(now, static_cast<double>(steps));
  const double since = now - last_;
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
  if (open_line_) std::fputs("\n", out_);
  fmt::print(out_, "cosim: reached t = {:.6g} s in {} coupling steps, wall {}\n", t, steps,
             util::clockDuration(clock_() - start_));
  std::fflush(out_);
  open_line_ = false;
}

void Progress::abort() {
  if (open_line_) std::fputs("\n", out_);
  open_line_ = false;
  std::fflush(out_);
}

}  // namespace cosim::orchestrator
