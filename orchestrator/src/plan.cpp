#include "plan.h"

#include <algorithm>
#include <set>

#include "cosim/link/fields.h"
#include "cosim/models/registry.h"

namespace cosim::orchestrator {

SceneModels makeModels(const Scenario& sc) {
  auto& r = models::Registry::instance();
  SceneModels m;
  if (sc.models.drag) m.drag = r.makeDrag(sc.models.drag->law, sc.models.drag->params);
  for (const auto& f : sc.models.forces) m.forces.push_back(r.makeForce(f.law, f.params));
  if (sc.models.mass_transfer)
    m.mass_transfer =
        r.makeMassTransfer(sc.models.mass_transfer->law, sc.models.mass_transfer->params);
  if (sc.models.coating_zone)
    m.zone = r.makeZone(sc.models.coating_zone->law, sc.models.coating_zone->params);
  return m;
}

Plan makePlan(const Scenario& sc, const SceneModels& m) {
  Plan p;
  std::set<std::string> needed;
  auto add = [&](const models::Model& model) {
    for (const auto& f : model.requiredFields()) needed.insert(f);
  };
  if (m.drag) add(*m.drag);
  for (const auto& f : m.forces) add(*f);
  if (m.mass_transfer) add(*m.mass_transfer);
  if (m.zone) add(*m.zone);

  p.coating = static_cast<bool>(m.mass_transfer);
  p.fluid = m.drag || !m.forces.empty() || m.mass_transfer;

  // Particle state: always position, velocity, radius (monitors, recording, locating).
  p.particles_send = {field::position, field::velocity, field::radius};
  if (p.coating) p.particles_send.push_back(field::coating_mass);

  if (m.drag) {
    p.particles_receive.push_back(field::drag_coefficient);
    p.particles_receive.push_back(field::fluid_velocity);
    needed.insert(field::fluid_velocity);
  }
  if (!m.forces.empty()) p.particles_receive.push_back(field::explicit_force);
  if (p.coating) p.particles_receive.push_back(field::coating_increment);

  if (p.fluid) {
    static const std::vector<std::string> fluid_side = {
        field::fluid_velocity,  field::voidage,           field::fluid_density,
        field::fluid_viscosity, field::pressure_gradient, field::precursor_fraction,
        field::cell_size};
    for (const auto& f : fluid_side) {
      if (needed.count(f)) p.fluid_send.push_back(f);
    }
    if (p.coating) p.fluid_send.push_back(field::precursor_removed);
    p.fluid_receive = {field::position, field::radius, field::velocity};
    if (m.drag) p.fluid_receive.push_back(field::drag_coefficient);
    if (p.coating) p.fluid_receive.push_back(field::transfer_coefficient);
  }

  if (!p.fluid && sc.participants.count("fluid")) {
    p.notes.push_back(
        "participant 'fluid' is configured but no model needs the fluid (no drag, forces or mass "
        "transfer): it is not started");
  }
  if (p.fluid && !p.coating) {
    p.notes.push_back("no mass transfer configured: no precursor species is solved or sent");
  }
  return p;
}

}  // namespace cosim::orchestrator
