#include "cosim/models/zone/box.h"

namespace cosim::models {

BoxZone::BoxZone(const Parameters& p) {
  p.rejectUnknown({"min", "max"});
  lo_ = readPoint(p, "min");
  hi_ = readPoint(p, "max");
  for (int j = 0; j < 3; ++j) {
    if (!(lo_[j] < hi_[j])) {
      throw ModelError(p.owner() + ": 'min' must be below 'max' in every component (component " +
                       std::to_string(j) + " is not)");
    }
  }
}

bool BoxZone::contains(const double* x) const {
  for (int j = 0; j < 3; ++j) {
    if (x[j] < lo_[j] || x[j] > hi_[j]) return false;
  }
  return true;
}

}  // namespace cosim::models
