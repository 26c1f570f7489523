#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

class StokesDrag final : public DragLaw {
 public:
  explicit StokesDrag(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "stokes"; }
  std::vector<std::string> requiredFields() const override {
    return {"radius", "velocity", "fluid_velocity", "fluid_viscosity"};
  }
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
};

}  // namespace cosim::models
