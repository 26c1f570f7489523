// Gunn (1978), Int. J. Heat Mass Transfer 21:467-476, original coefficients:
//   Sh = (7 - 10 eps + 5 eps^2)(1 + 0.7 Re^0.2 Sc^(1/3)) + (1.33 - 2.4 eps + 1.2 eps^2) Re^0.7
//   Sc^(1/3)
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double gunnSherwood(double eps, double Re, double Sc);

class GunnTransfer final : public MassTransferLaw {
 public:
  explicit GunnTransfer(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "gunn"; }
  std::vector<std::string> requiredFields() const override;
  void transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                            double* k) const override;
};

}  // namespace cosim::models
