#include "scenario/checks_section.h"

#include <cmath>

namespace cosim::orchestrator {

const std::vector<KeySpec>& ChecksSection::keys() {
  static const std::vector<KeySpec> k = {
      {"stability", "refuse", "refuse (stop unstable settings) | warn (only report them)"},
      {"max_particle_speed", "50", "a particle faster than this [m/s] stops the run; > 0"},
      {"mass_balance_tolerance", "1e-4", "relative precursor balance drift that stops the run"},
      {"max_courant", "5", "fluid Courant number that stops the run; > 0"},
      {"step_halvings", "0",
       "0: a run that max_courant stops stays stopped (continue it by hand with cosim resume, "
       "e.g. a smaller coupling.dt); N: cosim run and cosim resume take it back to its newest "
       "checkpoint and on with half the coupling step and half the DEM steps (the DEM step "
       "kept), to the first checkpoint half a checkpoint interval past the stop, then with "
       "coupling.dt again; halved again if that stops too, at most N times in a row (needs "
       "checkpoint.interval, and coupling.dem_steps divisible by 2^N); docs/restarts.md"},
      {"particle_count", "(not checked)",
       "particles the particle participant must hold when coupling starts (the scene's "
       "n_grains); another count (an insertion that could not place them all) stops the run "
       "before its first step, saying what was placed, its mass against the mass asked for "
       "(with constants.particle_density) and what to do"},
  };
  return k;
}

ChecksSection parseChecks(const YAML::Node& c, const Context& ctx) {
  ChecksSection out;
  if (!ctx.section(c, "checks", "{ stability: refuse, max_particle_speed: ... }")) return out;
  ctx.allowOnly(c, "checks", ChecksSection::keys());
  if (c["max_courant"]) out.max_courant = ctx.positive(c["max_courant"], "checks.max_courant", "");
  if (c["step_halvings"]) {
    const double n = ctx.number(c["step_halvings"], "checks.step_halvings");
    if (n < 0 || n != std::floor(n) || n > 20)
      ctx.fail(c["step_halvings"], "checks.step_halvings",
               "expected a whole number of halvings, 0 to 20, got " + c["step_halvings"].Scalar());
    out.step_halvings = static_cast<unsigned>(n);
  }
  if (c["stability"]) {
    out.stability = ctx.text(c["stability"], "checks.stability");
    if (out.stability != "refuse" && out.stability != "warn") {
      ctx.fail(c["stability"], "checks.stability",
               "expected 'refuse' (stop unstable settings) or 'warn'");
    }
  }
  if (c["max_particle_speed"])
    out.max_particle_speed =
        ctx.positive(c["max_particle_speed"], "checks.max_particle_speed", "(m/s)");
  if (c["mass_balance_tolerance"])
    out.mass_balance_tolerance =
        ctx.positive(c["mass_balance_tolerance"], "checks.mass_balance_tolerance", "");
  if (c["particle_count"]) {
    const double n = ctx.positive(c["particle_count"], "checks.particle_count", "(particles)");
    if (n != std::floor(n) || n > 1e15)
      ctx.fail(c["particle_count"], "checks.particle_count",
               "expected a whole number of particles, e.g. ${n_grains}");
    out.particle_count = static_cast<std::uint64_t>(n);
  }
  return out;
}

}  // namespace cosim::orchestrator
