// Cylinder coating zone. Parameters: base [x,y,z] (centre of the bottom disc), axis [x,y,z]
// (direction, any length), radius > 0, length > 0. Inside: 0 <= s <= length, r <= radius.
#pragma once

#include "cosim/models/model.h"
#include "cosim/models/zone/geometry.h"

namespace cosim::models {

class CylinderZone final : public CoatingZone {
 public:
  explicit CylinderZone(const Parameters& p);
  std::string name() const override { return "cylinder"; }
  bool contains(const double* x) const override;

 private:
  Vec3 base_{}, axis_{};
  double radius_ = 0, length_ = 0;
};

}  // namespace cosim::models
