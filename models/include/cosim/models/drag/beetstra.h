// Beetstra, van der Hoef & Kuipers (2007), AIChE J. 53:489-501, with phi = 1 - eps:
//   F(eps, Re) = 10 phi / eps^2 + eps^2 (1 + 1.5 sqrt(phi))
//              + [0.413 Re / (24 eps^2)] [1/eps + 3 eps phi + 8.4 Re^-0.343]
//                                        / [1 + 10^(3 phi) Re^(-(1 + 4 phi)/2)]
//   per real particle K = 3 pi mu d eps F   (so f = eps F; F(1, 0) = 1: Stokes)
// Options (parameters):
//   filtered: true|false (default false)  Radl & Sundaresan (2014) correction (radl_sundaresan.h);
//             needs particle_density [kg/m3] and the "cell_size" field.
//   k: number (default 0.05)  parcel-size factor exp(k (1 - cg)); applied when filtered is true
//             or when k is given explicitly (k: 0 switches it off).
//   particle_density: real particle density for the terminal velocity (required with filtered).
//   reference_fluid_density [kg/m3], reference_fluid_viscosity [Pa s] (optional, both or neither):
//             compute the terminal velocity once from these (as CFDEMcoupling does) instead of
//             from each parcel's local gas state.
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double beetstraF(double eps, double Re);  // F above; finite for Re = 0

class BeetstraDrag final : public DragLaw {
 public:
  explicit BeetstraDrag(const Parameters& p);
  std::string name() const override { return "beetstra"; }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
  // Filtered with the gas at each parcel: the terminal velocity's Newton starts from the last
  // parcel's (the reference gas has one terminal velocity for the whole batch)
  bool carriesAcrossParcels() const override { return filtered_ && reference_density_ <= 0.0; }

  bool filtered() const { return filtered_; }
  bool parcelFactor() const { return parcel_factor_; }
  double k() const { return k_; }

 private:
  bool filtered_ = false;
  bool parcel_factor_ = false;
  double k_ = 0.05;
  double particle_density_ = 0.0;
  double reference_density_ = 0.0;  // > 0: terminal velocity from the reference gas state
  double reference_viscosity_ = 0.0;
};

}  // namespace cosim::models
