#include "cosim/models/scene_models.h"

#include "cosim/models/drag/undisturbed_velocity.h"
#include "cosim/models/registry.h"

namespace cosim::models {

SceneModels makeSceneModels(const SceneModelChoices& c) {
  auto& r = Registry::instance();
  SceneModels m;
  if (c.drag) m.drag = r.makeDrag(c.drag->law, c.drag->params);
  if (const auto* u = dynamic_cast<const UndisturbedVelocityDrag*>(m.drag.get());
      u != nullptr && u->transient()) {
    m.wake = std::make_unique<WakeBuildup>();
  }
  for (const auto& f : c.forces) m.forces.push_back(r.makeForce(f.law, f.params));
  if (c.mass_transfer)
    m.mass_transfer = r.makeMassTransfer(c.mass_transfer->law, c.mass_transfer->params);
  if (c.coating_zone) m.zone = r.makeZone(c.coating_zone->law, c.coating_zone->params);
  m.splittable = c.plugins.empty() && !(m.drag && m.drag->carriesAcrossParcels()) &&
                 !(m.mass_transfer && m.mass_transfer->carriesAcrossParcels()) &&
                 !(m.zone && m.zone->carriesAcrossParcels());
  for (const auto& f : m.forces) m.splittable = m.splittable && !f->carriesAcrossParcels();
  return m;
}

}  // namespace cosim::models
