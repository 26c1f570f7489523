#include "cosim/liggghts/timestep_check.h"

#include <fmt/format.h>

#include <algorithm>

namespace cosim::liggghts {

TimestepVerdict judgeTimestep(const TimestepReport& r) {
  TimestepVerdict v;
  if (!r.has_particles) {
    v.summary = fmt::format("DEM dt {:.3g} s: no particles yet, nothing to check", r.dt);
    return v;
  }
  v.suggested_dt =
      std::min(kWarnRayleighFraction * r.rayleigh_time, kWarnHertzFraction * r.hertz_time);
  v.summary = fmt::format(
      "DEM dt {:.3g} s = {:.3g} x Rayleigh time ({:.3g} s) and {:.3g} x Hertz contact time "
      "({:.3g} s at {:.3g} m/s impact), smallest radius {:.3g} m",
      r.dt, r.dtOverRayleigh(), r.rayleigh_time, r.dtOverHertz(), r.hertz_time, r.impact_speed,
      r.min_radius);
  if (r.dtOverRayleigh() > kRefuseRayleighFraction || r.dtOverHertz() > kRefuseHertzFraction)
    v.verdict = Verdict::unstable;
  else if (r.dtOverRayleigh() > kWarnRayleighFraction || r.dtOverHertz() > kWarnHertzFraction)
    v.verdict = Verdict::doubtful;
  return v;
}

}  // namespace cosim::liggghts
