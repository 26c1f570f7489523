#include "scenario/constants_section.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& ConstantsSection::keys() {
  static const std::vector<KeySpec> k = {
      {"cg", "1", "coarse-graining factor (parcel diameter / real diameter); >= 1"},
      {"min_voidage", "0.35",
       "the voidage is clamped to [min_voidage, 1] before any law sees it; in (0, 1)"},
      {"gravity", "[0, 0, -9.81]", "gravity [m/s2], three numbers"},
      {"schmidt", "1", "Schmidt number mu / (rho D) of the precursor; > 0"},
      {"particle_density", "unknown (the checks that need it are skipped)",
       "particle density [kg/m3], > 0: the stability checks and checks.particle_count's mass. A "
       "particle participant that reports its own material (LIGGGHTS does, from its script) is "
       "judged with that; this value is then only compared with it (a warning names a "
       "difference of more than 1 %)"},
      {"youngs_modulus", "unknown (the Rayleigh-time check is skipped)",
       "Young's modulus [Pa] for the Rayleigh-time check, > 0; as particle_density, only "
       "compared with the participant's own when it reports one"},
      {"poisson_ratio", "0.3", "Poisson ratio for the Rayleigh-time check; in (-1, 0.5)"},
  };
  return k;
}

ConstantsSection parseConstants(const YAML::Node& c, const Context& ctx) {
  ConstantsSection out;
  if (!ctx.section(c, "constants", "{ cg: ..., min_voidage: ..., particle_density: ... }"))
    return out;
  ctx.allowOnly(c, "constants", ConstantsSection::keys());
  if (c["particle_density"])
    out.material.particle_density =
        ctx.positive(c["particle_density"], "constants.particle_density", "(kg/m3)");
  if (c["youngs_modulus"])
    out.material.youngs_modulus =
        ctx.positive(c["youngs_modulus"], "constants.youngs_modulus", "(Pa)");
  if (c["poisson_ratio"]) {
    out.material.poisson_ratio = ctx.number(c["poisson_ratio"], "constants.poisson_ratio");
    if (out.material.poisson_ratio <= -1 || out.material.poisson_ratio >= 0.5) {
      ctx.fail(c["poisson_ratio"], "constants.poisson_ratio",
               "expected a Poisson ratio in (-1, 0.5)");
    }
  }
  if (c["cg"]) {
    out.cg = ctx.number(c["cg"], "constants.cg");
    if (out.cg < 1.0) {
      ctx.fail(c["cg"], "constants.cg",
               "coarse-graining factor must be >= 1 (1 = real particles), got " + c["cg"].Scalar());
    }
  }
  if (c["min_voidage"]) {
    out.min_voidage = ctx.number(c["min_voidage"], "constants.min_voidage");
    if (out.min_voidage <= 0.0 || out.min_voidage >= 1.0) {
      ctx.fail(c["min_voidage"], "constants.min_voidage",
               "expected a voidage in (0, 1), e.g. 0.35");
    }
  }
  if (c["gravity"]) {
    if (!c["gravity"].IsSequence() || c["gravity"].size() != 3) {
      ctx.fail(c["gravity"], "constants.gravity", "expected three numbers [gx, gy, gz] in m/s2");
    }
    for (std::size_t i = 0; i < 3; ++i)
      out.gravity[i] = ctx.number(c["gravity"][i], "constants.gravity");
  }
  if (c["schmidt"]) out.schmidt = ctx.positive(c["schmidt"], "constants.schmidt", "");
  return out;
}

}  // namespace cosim::orchestrator
