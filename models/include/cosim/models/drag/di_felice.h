// Di Felice (1994), Int. J. Multiphase Flow 20:153-159:
//   F = Cd rho (pi d^2/4) eps^2 w^2 / 2 * eps^(-chi),  Re = rho eps d w / mu
//   chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2)
//   => f = K / (3 pi mu d) = (Cd Re / 24) eps^(1 - chi)
// Single-sphere Cd, parameter `drag_coefficient`:
//   "schiller_naumann" (default): Cd Re = 24 (1 + 0.15 Re^0.687) (Re < 1000), 0.44 Re above;
//      reduces exactly to Stokes as Re -> 0, eps -> 1.
//   "dallavalle" (Di Felice's original): Cd = (0.63 + 4.8 / sqrt(Re))^2; its Re -> 0 limit is
//      23.04/24 = 0.96 of Stokes drag.
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double diFeliceExponent(double Re);  // chi(Re); 3.7 at Re = 0

class DiFeliceDrag final : public DragLaw {
 public:
  explicit DiFeliceDrag(const Parameters& p);
  std::string name() const override { return "di_felice"; }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
  // f(eps, Re) = K / (3 pi mu d)
  double dimensionless(double eps, double Re) const;

 private:
  bool dallavalle_ = false;
};

}  // namespace cosim::models
