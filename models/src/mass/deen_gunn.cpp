#include "cosim/models/mass/deen_gunn.h"

#include <cmath>
#include <limits>

#include "cosim/models/mass/sherwood_transfer.h"

namespace cosim::models {

namespace {
double sherwood(double eps, double Re, double sc13) {
  // Re^0.2 and Re^0.7 from one logarithm
  const double lnRe = Re > 0.0 ? std::log(Re) : -std::numeric_limits<double>::infinity();
  return (7.0 - 10.0 * eps + 5.0 * eps * eps) * (1.0 + 0.17 * std::exp(0.2 * lnRe) * sc13) +
         (1.33 - 2.31 * eps + 1.16 * eps * eps) * std::exp(0.7 * lnRe) * sc13;
}
}  // namespace

double deenGunnSherwood(double eps, double Re, double Sc) {
  return sherwood(eps, Re, std::cbrt(Sc));
}

std::vector<std::string> DeenGunnTransfer::requiredFields() const { return massTransferFields(); }

void DeenGunnTransfer::transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                                            double* k) const {
  evaluateTransfer(*this, p, c, k, sherwood);
}

}  // namespace cosim::models
