#include "cosim/models/drag/di_felice.h"

#include <cmath>

#include "cosim/models/drag/dimensionless_drag.h"
#include "cosim/models/drag/schiller_naumann.h"

namespace cosim::models {

double diFeliceExponent(double Re) {
  if (!(Re > 0.0)) return 3.7;  // exp(-(1.5 - log10 0)^2 / 2) = 0
  const double t = 1.5 - std::log10(Re);
  return 3.7 - 0.65 * std::exp(-0.5 * t * t);
}

DiFeliceDrag::DiFeliceDrag(const Parameters& p) {
  p.rejectUnknown({"drag_coefficient"});
  const std::string cd = p.text("drag_coefficient", "schiller_naumann");
  if (cd == "dallavalle") {
    dallavalle_ = true;
  } else if (cd != "schiller_naumann") {
    throw ModelError(p.owner() + ": parameter 'drag_coefficient' = '" + cd +
                     "'; expected schiller_naumann (default) or dallavalle");
  }
}

std::vector<std::string> DiFeliceDrag::requiredFields() const { return denseDragFields(); }

double DiFeliceDrag::dimensionless(double eps, double Re) const {
  // Cd Re / 24 without dividing by Re: Dallavalle Cd Re = (0.63 sqrt(Re) + 4.8)^2.
  double cdre24;
  if (dallavalle_) {
    const double a = 0.63 * std::sqrt(Re) + 4.8;
    cdre24 = a * a / 24.0;
  } else {
    cdre24 = schillerNaumannCorrection(Re);
  }
  return cdre24 * std::pow(eps, 1.0 - diFeliceExponent(Re));
}

void DiFeliceDrag::coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const {
  evaluateDrag(*this, p, c, K, [this](double eps, double Re) { return dimensionless(eps, Re); });
}

}  // namespace cosim::models
