// Every built-in model, registered by name. Add a line here when you add a law.
#include "cosim/models/drag/stokes.h"
#include "cosim/models/registry.h"

namespace cosim::models {

void registerBuiltins(Registry& r) {
  r.addDrag("stokes", [](const Parameters& p) { return std::make_unique<StokesDrag>(p); });
}

}  // namespace cosim::models
