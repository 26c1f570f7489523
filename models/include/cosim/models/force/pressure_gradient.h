// Pressure-gradient (buoyancy) force on a parcel: F = -V_parcel grad p, V_parcel = 4/3 pi r^3
// (parcel radius r: the parcel displaces the volume of its cg^3 real particles).
// In still gas grad p = rho_f g, so F = -rho_f V g: the buoyancy, and a bed at rest carries
// its weight minus buoyancy.
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

class PressureGradientForce final : public ForceModel {
 public:
  explicit PressureGradientForce(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "pressure_gradient"; }
  std::vector<std::string> requiredFields() const override {
    return {"radius", "pressure_gradient"};
  }
  void addForces(const ParcelBatch& p, const SceneConstants& c, double* force) const override;
};

}  // namespace cosim::models
