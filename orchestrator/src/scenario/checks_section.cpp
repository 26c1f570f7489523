#include "scenario/checks_section.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& ChecksSection::keys() {
  static const std::vector<KeySpec> k = {
      {"stability", "refuse", "refuse (stop unstable settings) | warn (only report them)"},
      {"max_particle_speed", "50", "a particle faster than this [m/s] stops the run; > 0"},
      {"mass_balance_tolerance", "1e-4", "relative precursor balance drift that stops the run"},
      {"max_courant", "5", "fluid Courant number that stops the run; > 0"},
  };
  return k;
}

ChecksSection parseChecks(const YAML::Node& c, const Context& ctx) {
  ChecksSection out;
  if (!ctx.section(c, "checks", "{ stability: refuse, max_particle_speed: ... }")) return out;
  ctx.allowOnly(c, "checks", ChecksSection::keys());
  if (c["max_courant"]) out.max_courant = ctx.positive(c["max_courant"], "checks.max_courant", "");
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
  return out;
}

}  // namespace cosim::orchestrator
