// Sphere coating zone. Parameters: center [x,y,z], radius > 0. Inside: |x - center| <= radius.
#pragma once

#include "cosim/models/model.h"
#include "cosim/models/zone/geometry.h"

namespace cosim::models {

class SphereZone final : public CoatingZone {
 public:
  explicit SphereZone(const Parameters& p);
  std::string name() const override { return "sphere"; }
  bool contains(const double* x) const override;

 private:
  Vec3 center_{};
  double radius_ = 0;
};

}  // namespace cosim::models
