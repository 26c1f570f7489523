#include "cosim/models/zone/union.h"

#include "cosim/models/registry.h"

namespace cosim::models {

UnionZone::UnionZone(const Parameters& p) {
  p.rejectUnknown({"parts"});
  const auto& parts = p.children("parts");
  if (parts.empty()) {
    throw ModelError(p.owner() + ": parameter 'parts' is empty; list at least one zone");
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const Parameters& part = parts[i];
    const std::string where = p.owner() + " part " + std::to_string(i + 1);
    if (!part.has("shape")) {
      throw ModelError(where +
                       ": missing parameter 'shape' (one of: cylinder, cone_frustum, "
                       "box, sphere, union)");
    }
    const std::string shape = part.text("shape");
    try {
      parts_.push_back(
          Registry::instance().makeZone(shape, part.without("shape", where + " (" + shape + ")")));
    } catch (const ModelError& e) {
      // Unknown shape names come back from the registry without the position in the union.
      if (std::string(e.what()).find(where) == std::string::npos) {
        throw ModelError(where + ": " + e.what());
      }
      throw;
    }
  }
}

bool UnionZone::contains(const double* x) const {
  for (const auto& z : parts_) {
    if (z->contains(x)) return true;
  }
  return false;
}

}  // namespace cosim::models
