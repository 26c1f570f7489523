#include "cosim/models/zone/sphere.h"

namespace cosim::models {

SphereZone::SphereZone(const Parameters& p) {
  p.rejectUnknown({"center", "radius"});
  center_ = readPoint(p, "center");
  radius_ = p.positive("radius");
}

bool SphereZone::contains(const double* x) const {
  const Vec3 r = minus(x, center_);
  return dot(r, r) <= radius_ * radius_;
}

}  // namespace cosim::models
