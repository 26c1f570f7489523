#include "cosim/liggghts/adapter_options.h"

#include "cosim/util/errors.h"

namespace cosim::liggghts {

const std::vector<util::OptionSpec>& AdapterOptions::specs() {
  static const std::vector<util::OptionSpec> s = {
      {"script", "required",
       "the LIGGGHTS input script, relative to the participant's folder (the scene's files:)"},
      {"impact_speed", "2",
       "[m/s] the largest impact speed expected, for the Hertz contact time of the time-step "
       "check; > 0"},
      {"dt_check", "refuse",
       "what an unstable DEM time step does: refuse (the run does not start) | warn | off"},
  };
  return s;
}

AdapterOptions AdapterOptions::parse(const std::string& yaml_text) {
  const util::AdapterOptions in(yaml_text, "particles", "cosim-liggghts", specs(),
                                "docs/liggghts.md");
  if (in.empty())
    throw InputError(in.keyName("script") +
                     ": missing; the liggghts adapter needs at least `script: <your LIGGGHTS "
                     "input file>`");
  AdapterOptions o;
  o.script = in.requiredText("script", "in.liggghts");
  o.impact_speed = in.positive("impact_speed", o.impact_speed);
  const std::string check = in.choice("dt_check", "refuse", {"refuse", "warn", "off"});
  o.dt_check = check == "warn"  ? DtCheckPolicy::warn
               : check == "off" ? DtCheckPolicy::off
                                : DtCheckPolicy::refuse;
  return o;
}

}  // namespace cosim::liggghts
