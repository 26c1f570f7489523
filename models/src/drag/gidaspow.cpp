#include "cosim/models/drag/gidaspow.h"

#include <cmath>

#include "cosim/models/drag/dimensionless_drag.h"
#include "cosim/models/drag/schiller_naumann.h"

namespace cosim::models {

GidaspowDrag::GidaspowDrag(const Parameters& p) {
  p.rejectUnknown({"switch_voidage"});
  switch_voidage_ = p.has("switch_voidage") ? p.number("switch_voidage", 0.0, 1.0) : 0.8;
}

std::vector<std::string> GidaspowDrag::requiredFields() const { return denseDragFields(); }

double GidaspowDrag::dimensionless(double eps, double Re) const {
  if (eps < switch_voidage_) {
    const double phi = 1.0 - eps;
    return (25.0 / 3.0) * phi / eps + (1.75 / 18.0) * Re / eps;  // Ergun
  }
  return schillerNaumannCorrection(Re) * std::pow(eps, -2.65);  // Wen-Yu
}

void GidaspowDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  evaluateDrag(*this, p, c, K, [this](double eps, double Re) { return dimensionless(eps, Re); });
}

}  // namespace cosim::models
