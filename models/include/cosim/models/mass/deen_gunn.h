// Deen et al. (2014), Chem. Eng. Sci. 116:710-724: modified Gunn correlation (paper's choice):
//   Sh = (7 - 10 eps + 5 eps^2)(1 + 0.17 Re^0.2 Sc^(1/3)) + (1.33 - 2.31 eps + 1.16 eps^2) Re^0.7
//   Sc^(1/3)
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double deenGunnSherwood(double eps, double Re, double Sc);

class DeenGunnTransfer final : public MassTransferLaw {
 public:
  explicit DeenGunnTransfer(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "deen_gunn"; }
  std::vector<std::string> requiredFields() const override;
  void transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                            double* k) const override;
};

}  // namespace cosim::models
