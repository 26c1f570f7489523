#include "cosim/link/fields.h"

namespace cosim::field {

namespace {
const std::map<std::string, unsigned>& table() {
  static const std::map<std::string, unsigned> t = {
      {position, 3},          {velocity, 3},          {radius, 1},
      {coating_mass, 1},      {type, 1},              {fluid_velocity, 3},
      {voidage, 1},           {fluid_density, 1},     {fluid_viscosity, 1},
      {pressure_gradient, 3}, {precursor_fraction, 1}, {cell_size, 1},
      {drag_coefficient, 1},  {explicit_force, 3},    {coating_increment, 1},
      {transfer_coefficient, 1}, {precursor_removed, 1},
  };
  return t;
}
}  // namespace

unsigned components(const std::string& name) {
  auto it = table().find(name);
  return it == table().end() ? 0U : it->second;
}

const std::vector<std::string>& all() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& [k, c] : table()) v.push_back(k);
    return v;
  }();
  return names;
}

}  // namespace cosim::field
