// Checks on what a model receives and returns. Every error names the model, the field or
// constant, the parcel, the value, what was expected and where to look.
//   validateConstants: cg >= 1, min_voidage in (0, 1], schmidt > 0, gravity finite.
//   checkInputs: each declared field present; radius, fluid_density, fluid_viscosity,
//     cell_size finite and > 0; voidage finite in (0, 1] (1 + 1e-9 tolerated for round-off);
//     vectors finite. Zero viscosity is an evaluation error here (the fluid sends mu per parcel).
//   checkOutputs: nothing non-finite ever leaves a model.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cosim/models/parameters.h"
#include "cosim/models/parcels.h"

namespace cosim::models {

void validateConstants(const std::string& owner, const SceneConstants& c);
void checkInputs(const std::string& owner, const std::vector<std::string>& fields,
                 const ParcelBatch& p, const SceneConstants& c);
void checkOutputs(const std::string& owner, const char* what, const double* values,
                  std::size_t count);

}  // namespace cosim::models
