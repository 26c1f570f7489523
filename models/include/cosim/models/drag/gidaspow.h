// Gidaspow (1994): Ergun (1952) for eps < 0.8, Wen & Yu (1966) for eps >= 0.8.
// Per-volume coefficients beta, per particle K = beta V_p / (1 - eps); Re = rho eps d w / mu:
//   Ergun:  beta = 150 phi^2 mu / (eps d^2) + 1.75 phi rho w / d
//           => f = K / (3 pi mu d) = (25/3) phi / eps + (1.75/18) Re / eps
//   Wen-Yu: beta = (3/4) Cd eps phi rho w eps^-2.65 / d, Cd Re = 24 (1 + 0.15 Re^0.687) (Re<1000),
//           0.44 Re (Re >= 1000)  => f = (Cd Re / 24) eps^-2.65
// Parameter `switch_voidage` (default 0.8). The law is discontinuous at the switch (as published).
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

class GidaspowDrag final : public DragLaw {
 public:
  explicit GidaspowDrag(const Parameters& p);
  std::string name() const override { return "gidaspow"; }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
  double dimensionless(double eps, double Re) const;  // f(eps, Re)

 private:
  double switch_voidage_ = 0.8;
};

}  // namespace cosim::models
