#include "cosim/models/drag/koch_hill.h"

#include <cmath>

#include "cosim/models/drag/dimensionless_drag.h"

namespace cosim::models {

double kochHillF(double phi, double Re) {
  const double eps = 1.0 - phi;
  const double eps3 = eps * eps * eps;
  const double dense = 10.0 * phi / eps3;
  // w -> 0 and phi ln phi -> 0 as phi -> 0: evaluate the limits without 0 * inf.
  const double w = phi > 0.0 ? std::exp(-10.0 * (0.4 - phi) / phi) : 0.0;
  const double philnphi = phi > 0.0 ? phi * std::log(phi) : 0.0;
  const double root = 1.0 + 3.0 * std::sqrt(phi / 2.0) + 135.0 / 64.0 * philnphi;
  const double phi2 = phi * phi, phi3 = phi2 * phi;

  const double F0 = phi < 0.4 ? (1.0 - w) * (root + 17.14 * phi) /
                                        (1.0 + 0.681 * phi - 8.48 * phi2 + 8.16 * phi3) +
                                    w * dense
                              : dense;
  const double F2 = phi < 0.4 ? (1.0 - w) * (root + 17.89 * phi) /
                                        (1.0 + 0.681 * phi - 11.03 * phi2 + 15.41 * phi3) +
                                    w * dense
                              : dense;
  const double F3 =
      phi < 0.0953 ? 0.9351 * phi + 0.03667 : 0.0673 + 0.212 * phi + 0.0232 / (eps3 * eps * eps);
  if (phi <= 0.01) {
    const double re_t1 = (F2 - 1.0) / (3.0 / 8.0 - F3);
    return Re <= re_t1 ? 1.0 + 3.0 / 8.0 * Re : F2 + F3 * Re;
  }
  const double F1 = phi <= 0.1 ? std::sqrt(2.0 / phi) / 40.0 : 0.11 + 5.1e-4 * std::exp(11.6 * phi);
  const double disc = F3 * F3 - 4.0 * F1 * (F0 - F2);
  const double re_t2 = (F3 + std::sqrt(std::max(disc, 0.0))) / (2.0 * F1);
  return Re <= re_t2 ? F0 + F1 * Re * Re : F2 + F3 * Re;
}

std::vector<std::string> KochHillDrag::requiredFields() const { return denseDragFields(); }

void KochHillDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  evaluateDrag(*this, p, c, K,
               [](double eps, double Re) { return eps * eps * kochHillF(1.0 - eps, 0.5 * Re); });
}

}  // namespace cosim::models
