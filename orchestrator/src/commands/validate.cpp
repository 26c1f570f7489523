// cosim validate SCENARIO [--set K=V] [--unset K]: what a scene would start and send, and the
// numbers it marks to show (parameters with show: true), without running.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "adapter_check.h"
#include "commands.h"
#include "launchers.h"
#include "link_security.h"
#include "plan.h"
#include "scenario.h"

namespace cosim::orchestrator {

namespace {

int validate(const std::string& file, const std::vector<std::string>& sets,
             const std::vector<std::string>& unsets) {
  Scenario sc = loadScenario(file, sets, unsets);
  models::SceneModels m = makeModels(sc);
  Plan p = makePlan(sc, m);
  const auto checked = checkAdapters(sc, p);  // the adapters' own view of the scene
  std::cout << "scenario '" << sc.name << "' is valid (" << sc.file.string() << ")\n";
  std::cout << "  coupling: dt " << sc.coupling.dt << " s x " << sc.coupling.dem_steps
            << " DEM steps, t = " << sc.coupling.start_time << " .. " << sc.coupling.end_time
            << " s ("
            << static_cast<long long>(
                   std::llround((sc.coupling.end_time - sc.coupling.start_time) / sc.coupling.dt))
            << " steps), scheme " << sc.coupling.scheme << "\n";
  std::cout << "  particles: " << sc.participants.at("particles").adapter << "; sends "
            << joinNames(p.particles_send) << "; receives " << joinNames(p.particles_receive)
            << "\n";
  if (p.fluid) {
    std::cout << "  fluid: " << sc.participants.at("fluid").adapter << "; sends "
              << joinNames(p.fluid_send) << "; receives " << joinNames(p.fluid_receive) << "\n";
  }
  std::cout << "  models: drag " << (sc.models.drag ? sc.models.drag->law : "none") << ", forces "
            << sc.models.forces.size() << ", mass transfer "
            << (sc.models.mass_transfer ? sc.models.mass_transfer->law : "none")
            << ", coating zone " << (sc.models.coating_zone ? sc.models.coating_zone->law : "none")
            << "\n";
  std::cout << "  link: " << linkDescription(sc.transport) << "\n";
  for (const auto& [name, spec] : sc.participants) {
    if (name == "fluid" && !p.fluid) continue;
    const bool curve = isTcp(sc.transport.bind) && !sc.transport.insecure;
    std::cout << "  launch " << name << ": " << describeLaunch(spec)
              << (!curve ? ""
                  : spec.launch != "external"
                      ? "; its run keys through the environment"
                      : "; its run keys in RUN/.cosim-" + name + ".key (--key-file)")
              << "\n";
  }
  for (const auto& v : sc.shown)
    std::cout << "  shows: " << v.name << " = " << fmt::format("{:.6g}", v.value)
              << (v.doc.empty() ? "" : "  (" + v.doc + ")") << "\n";
  for (const auto& n : p.notes) std::cout << "  note: " << n << "\n";
  for (const auto& a : checked) std::cout << "  checked: " << a << "\n";
  std::cout << "  output: " << sc.output.folder.string() << "\n";
  return 0;
}

}  // namespace

void addValidateCommand(CLI::App& app, Commands& commands) {
  struct Options {
    std::string scenario;
    std::vector<std::string> sets, unsets;
  };
  auto o = std::make_shared<Options>();
  auto* val = app.add_subcommand(
      "validate", "Check a scenario and show what it would start and send, without running");
  val->add_option("scenario", o->scenario, "scenario file or folder")->required();
  val->add_option("--set", o->sets, "override a value (as for run)")->take_all();
  val->add_option("--unset", o->unsets, "remove a node (as for run)")->take_all();
  commands.push_back({val, [o] { return validate(o->scenario, o->sets, o->unsets); }});
}

}  // namespace cosim::orchestrator
