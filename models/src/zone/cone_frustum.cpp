#include "cosim/models/zone/cone_frustum.h"

#include <limits>

namespace cosim::models {

ConeFrustumZone::ConeFrustumZone(const Parameters& p) {
  p.rejectUnknown({"base", "axis", "length", "base_radius", "top_radius"});
  base_ = readPoint(p, "base");
  axis_ = readDirection(p, "axis");
  length_ = p.positive("length");
  r0_ = p.number("base_radius", 0.0, std::numeric_limits<double>::infinity());
  r1_ = p.number("top_radius", 0.0, std::numeric_limits<double>::infinity());
  if (r0_ == 0.0 && r1_ == 0.0) {
    throw ModelError(p.owner() +
                     ": base_radius and top_radius are both 0; at least one must "
                     "be > 0");
  }
}

bool ConeFrustumZone::contains(const double* x) const {
  const AxialPosition a = axialPosition(x, base_, axis_);
  if (a.s < 0.0 || a.s > length_) return false;
  const double R = r0_ + (r1_ - r0_) * (a.s / length_);
  return a.r2 <= R * R;
}

}  // namespace cosim::models
