// Parcel coating per real grain and as a layer thickness (grain_scale.h).
#include "cosim/analysis/grain_scale.h"

#include <cmath>
#include <numbers>

namespace cosim::analysis {

double GrainScale::perGrain(double parcel_kg) const { return parcel_kg / (cg * cg * cg); }

double GrainScale::thickness(double parcel_kg) const {
  if (!(grain_diameter > 0 && coating_density > 0)) return std::numeric_limits<double>::quiet_NaN();
  return perGrain(parcel_kg) /
         (coating_density * std::numbers::pi * grain_diameter * grain_diameter);
}

}  // namespace cosim::analysis
