// Every built-in model, registered by name. Add a line here when you add a law.
#include "cosim/models/drag/beetstra.h"
#include "cosim/models/drag/di_felice.h"
#include "cosim/models/drag/gidaspow.h"
#include "cosim/models/drag/koch_hill.h"
#include "cosim/models/drag/schiller_naumann.h"
#include "cosim/models/drag/stokes.h"
#include "cosim/models/force/pressure_gradient.h"
#include "cosim/models/mass/deen_gunn.h"
#include "cosim/models/mass/gunn.h"
#include "cosim/models/mass/ranz_marshall.h"
#include "cosim/models/registry.h"
#include "cosim/models/zone/box.h"
#include "cosim/models/zone/cone_frustum.h"
#include "cosim/models/zone/cylinder.h"
#include "cosim/models/zone/sphere.h"
#include "cosim/models/zone/union.h"

namespace cosim::models {

namespace {
template <class Base, class T>
Registry::Factory<Base> factory() {
  return [](const Parameters& p) -> std::unique_ptr<Base> { return std::make_unique<T>(p); };
}
}  // namespace

void registerBuiltins(Registry& r) {
  r.addDrag("stokes", factory<DragLaw, StokesDrag>());
  r.addDrag("schiller_naumann", factory<DragLaw, SchillerNaumannDrag>());
  r.addDrag("di_felice", factory<DragLaw, DiFeliceDrag>());
  r.addDrag("gidaspow", factory<DragLaw, GidaspowDrag>());
  r.addDrag("koch_hill", factory<DragLaw, KochHillDrag>());
  r.addDrag("beetstra", factory<DragLaw, BeetstraDrag>());

  r.addForce("pressure_gradient", factory<ForceModel, PressureGradientForce>());

  r.addMassTransfer("deen_gunn", factory<MassTransferLaw, DeenGunnTransfer>());
  r.addMassTransfer("gunn", factory<MassTransferLaw, GunnTransfer>());
  r.addMassTransfer("ranz_marshall", factory<MassTransferLaw, RanzMarshallTransfer>());

  r.addZone("cylinder", factory<CoatingZone, CylinderZone>());
  r.addZone("cone_frustum", factory<CoatingZone, ConeFrustumZone>());
  r.addZone("box", factory<CoatingZone, BoxZone>());
  r.addZone("sphere", factory<CoatingZone, SphereZone>());
  r.addZone("union", factory<CoatingZone, UnionZone>());
}

}  // namespace cosim::models
