#include "cosim/link/fields.h"

namespace cosim::field {

namespace {
struct Info {
  unsigned components;
  const char* units;
  const char* description;
};

const std::map<std::string, Info>& table() {
  static const std::map<std::string, Info> t = {
      {position, {3, "m", "parcel centre position (x, y, z)"}},
      {velocity, {3, "m/s", "parcel velocity (x, y, z)"}},
      {radius, {1, "m", "parcel radius as simulated (cg times the radius of the real grains)"}},
      {coating_mass,
       {1, "kg", "coating deposited on the parcel, i.e. on the cg^3 real grains it stands for"}},
      {type, {1, "-", "particle type number of the particles participant"}},
      {fluid_velocity, {3, "m/s", "gas velocity at the parcel (x, y, z)"}},
      {voidage, {1, "-", "gas volume fraction at the parcel"}},
      {fluid_density, {1, "kg/m3", "gas density at the parcel"}},
      {fluid_viscosity, {1, "Pa s", "dynamic gas viscosity at the parcel"}},
      {pressure_gradient, {3, "Pa/m", "gas pressure gradient at the parcel (x, y, z)"}},
      {precursor_fraction, {1, "-", "precursor mass fraction in the gas at the parcel"}},
      {cell_size, {1, "m", "size of the fluid cell holding the parcel, V_cell^(1/3)"}},
      {drag_coefficient, {1, "kg/s", "drag coefficient K of the parcel: F = K (u_f - v)"}},
      {explicit_force, {3, "N", "force on the parcel held constant over a coupling step"}},
      {coating_increment, {1, "kg", "coating credited to the parcel over one coupling step"}},
      {transfer_coefficient,
       {1, "kg/s", "precursor uptake of the parcel per unit precursor mass fraction"}},
      {precursor_removed, {1, "kg", "precursor the parcel removed from the gas over a step"}},
  };
  return t;
}

const Info* find(const std::string& name) {
  auto it = table().find(name);
  return it == table().end() ? nullptr : &it->second;
}
}  // namespace

unsigned components(const std::string& name) {
  const Info* i = find(name);
  return i ? i->components : 0U;
}

const char* units(const std::string& name) {
  const Info* i = find(name);
  return i ? i->units : "";
}

const char* description(const std::string& name) {
  const Info* i = find(name);
  return i ? i->description : "";
}

const std::vector<std::string>& all() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& [k, info] : table()) v.push_back(k);
    return v;
  }();
  return names;
}

}  // namespace cosim::field
