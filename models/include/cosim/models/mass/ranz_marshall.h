// Ranz & Marshall (1952), Chem. Eng. Prog. 48:141-146, single sphere:
//   Sh = 2 + 0.6 Re^0.5 Sc^(1/3)   (voidage enters only through Re, project convention)
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double ranzMarshallSherwood(double Re, double Sc);

class RanzMarshallTransfer final : public MassTransferLaw {
 public:
  explicit RanzMarshallTransfer(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "ranz_marshall"; }
  std::vector<std::string> requiredFields() const override;
  void transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                            double* k) const override;
};

}  // namespace cosim::models
