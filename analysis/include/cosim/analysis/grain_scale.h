// From a parcel to the real grains it stands for. A coarse-grained parcel of diameter D stands
// for cg^3 real grains of diameter d = D / cg, so its coating mass m is shared by cg^3 grains:
//   coating per real grain   m_g = m / cg^3
//   layer thickness          h   = m_g / (rho_c pi d^2)
// (a thin layer of density rho_c on the grain's surface pi d^2; h << d). docs/analysis.md
// section 8.
#pragma once

#include <limits>

namespace cosim::analysis {

struct GrainScale {
  double cg = 1.0;                                                    // coarse-graining factor
  double grain_diameter = std::numeric_limits<double>::quiet_NaN();   // [m] real grain, D / cg
  double coating_density = std::numeric_limits<double>::quiet_NaN();  // [kg/m3] of the layer

  // [kg] coating of one real grain for a parcel's coating of parcel_kg.
  double perGrain(double parcel_kg) const;
  // [m] the layer that coating makes on one real grain (NaN without diameter or density).
  double thickness(double parcel_kg) const;
};

}  // namespace cosim::analysis
