// Axis-aligned box coating zone. Parameters: min [x,y,z], max [x,y,z] with min < max in every
// component. Inside: min <= x <= max component-wise.
#pragma once

#include "cosim/models/model.h"
#include "cosim/models/zone/geometry.h"

namespace cosim::models {

class BoxZone final : public CoatingZone {
 public:
  explicit BoxZone(const Parameters& p);
  std::string name() const override { return "box"; }
  bool contains(const double* x) const override;

 private:
  Vec3 lo_{}, hi_{};
};

}  // namespace cosim::models
