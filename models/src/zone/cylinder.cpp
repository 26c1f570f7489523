#include "cosim/models/zone/cylinder.h"

namespace cosim::models {

CylinderZone::CylinderZone(const Parameters& p) {
  p.rejectUnknown({"base", "axis", "radius", "length"});
  base_ = readPoint(p, "base");
  axis_ = readDirection(p, "axis");
  radius_ = p.positive("radius");
  length_ = p.positive("length");
}

bool CylinderZone::contains(const double* x) const {
  const AxialPosition a = axialPosition(x, base_, axis_);
  return a.s >= 0.0 && a.s <= length_ && a.r2 <= radius_ * radius_;
}

}  // namespace cosim::models
