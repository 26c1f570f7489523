// Schiller & Naumann (1933) single-sphere drag:
//   Cd = 24/Re (1 + 0.15 Re^0.687) for Re < 1000, 0.44 above;  F = Cd rho w^2 pi d^2 / 8
//   => f = K / (3 pi mu d) = 1 + 0.15 Re^0.687  (Re < 1000),  0.44 Re / 24  (Re >= 1000).
// Single-particle law: voidage enters only through Re (project convention, superficial slip).
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double schillerNaumannCorrection(double Re);  // f(Re) above

class SchillerNaumannDrag final : public DragLaw {
 public:
  explicit SchillerNaumannDrag(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "schiller_naumann"; }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
};

}  // namespace cosim::models
