#include "cosim/models/drag/schiller_naumann.h"

#include <cmath>

#include "cosim/models/drag/dimensionless_drag.h"

namespace cosim::models {

double schillerNaumannCorrection(double Re) {
  return Re < 1000.0 ? 1.0 + 0.15 * std::pow(Re, 0.687) : 0.44 * Re / 24.0;
}

std::vector<std::string> SchillerNaumannDrag::requiredFields() const { return denseDragFields(); }

void SchillerNaumannDrag::coefficients(const ParcelBatch& p, const SceneConstants& c,
                                       double* K) const {
  evaluateDrag(*this, p, c, K, [](double, double Re) { return schillerNaumannCorrection(Re); });
}

}  // namespace cosim::models
