#include "cosim/models/mass/ranz_marshall.h"

#include <cmath>

#include "cosim/models/mass/sherwood_transfer.h"

namespace cosim::models {

double ranzMarshallSherwood(double Re, double Sc) {
  return 2.0 + 0.6 * std::sqrt(Re) * std::cbrt(Sc);
}

std::vector<std::string> RanzMarshallTransfer::requiredFields() const {
  return massTransferFields();
}

void RanzMarshallTransfer::transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                                                double* k) const {
  evaluateTransfer(*this, p, c, k,
                   [](double, double Re, double sc13) { return 2.0 + 0.6 * std::sqrt(Re) * sc13; });
}

}  // namespace cosim::models
