// Cone-frustum coating zone. Parameters: base [x,y,z] (centre of the base disc), axis [x,y,z],
// length > 0, base_radius >= 0, top_radius >= 0 (not both 0). Radius varies linearly from
// base_radius at s = 0 to top_radius at s = length. Inside: 0 <= s <= length, r <= R(s).
#pragma once

#include "cosim/models/model.h"
#include "cosim/models/zone/geometry.h"

namespace cosim::models {

class ConeFrustumZone final : public CoatingZone {
 public:
  explicit ConeFrustumZone(const Parameters& p);
  std::string name() const override { return "cone_frustum"; }
  bool contains(const double* x) const override;

 private:
  Vec3 base_{}, axis_{};
  double r0_ = 0, r1_ = 0, length_ = 0;
};

}  // namespace cosim::models
