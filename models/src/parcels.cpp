#include "cosim/models/parcels.h"

namespace cosim::models {

ParcelBatch ParcelArrays::view() const {
  ParcelBatch b;
  b.n = size();
  for (const auto& f : kParcelFields) {
    const auto& v = this->*f.arrays;
    b.*f.batch = v.empty() ? nullptr : v.data();
  }
  return b;
}

}  // namespace cosim::models
