// Start-up check of the DEM time step against the Rayleigh time and the Hertz contact time of
// the smallest/softest particles (docs/physics.md section 7).
//   refuse: dt > 0.3 t_R  or  dt > t_H / 3
//   warn:   dt > 0.2 t_R  or  dt > t_H / 5
// A refusal names the dt that would work: min(0.2 t_R, t_H / 5).
#pragma once

#include <string>

#include "cosim/util/rayleigh_time.h"

namespace cosim::liggghts {

// DEM time step against the contact time scales of the current particles.
struct TimestepReport {
  bool has_particles = false;
  double dt = 0;
  double min_radius = 0;
  double rayleigh_time = 0;  // smallest over all particles
  double hertz_time = 0;     // smallest over all particles (rigid-wall impact at impact_speed)
  double impact_speed = 0;
  double dtOverRayleigh() const { return dt / rayleigh_time; }
  double dtOverHertz() const { return dt / hertz_time; }
};

// The Rayleigh limits are the orchestrator's too (cosim/util/rayleigh_time.h).
using util::kRefuseRayleighFraction;
using util::kWarnRayleighFraction;
inline constexpr double kRefuseHertzFraction = 1.0 / 3.0;
inline constexpr double kWarnHertzFraction = 0.2;

enum class Verdict { ok, doubtful, unstable };

struct TimestepVerdict {
  Verdict verdict = Verdict::ok;
  double suggested_dt = 0;  // min(0.2 t_R, t_H/5)
  std::string summary;      // one line with the ratios, always filled
};

TimestepVerdict judgeTimestep(const TimestepReport& report);

}  // namespace cosim::liggghts
