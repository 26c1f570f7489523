// Names and shapes of the per-particle fields that travel between the orchestrator and the
// adapters. A scene's packets carry only the fields its models need (negotiated at handshake).
// Header is C++17 so the OpenFOAM adapter can include it.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cosim::field {

// Particle state (particles participant -> orchestrator -> fluid)
inline constexpr const char* position = "position";          // [m] x3
inline constexpr const char* velocity = "velocity";          // [m/s] x3
inline constexpr const char* radius = "radius";              // [m] parcel radius (simulated)
inline constexpr const char* coating_mass = "coating_mass";  // [kg] per parcel
inline constexpr const char* type = "type";                  // particle type (integer)

// Fluid samples at particles (fluid -> orchestrator)
inline constexpr const char* fluid_velocity = "fluid_velocity";          // [m/s] x3
inline constexpr const char* voidage = "voidage";                        // [-]
inline constexpr const char* fluid_density = "fluid_density";            // [kg/m3]
inline constexpr const char* fluid_viscosity = "fluid_viscosity";        // [Pa s] dynamic
inline constexpr const char* pressure_gradient = "pressure_gradient";    // [Pa/m] x3
inline constexpr const char* precursor_fraction = "precursor_fraction";  // [-] mass fraction
inline constexpr const char* cell_size = "cell_size";                    // [m] V_cell^(1/3)

// Forcing for the particles (orchestrator -> particles)
inline constexpr const char* drag_coefficient = "drag_coefficient";  // K [kg/s]: F = K (u_f - v)
// fluid_velocity (above) is sent too
inline constexpr const char* explicit_force = "explicit_force";        // [N] x3, constant over dt
inline constexpr const char* coating_increment = "coating_increment";  // [kg] add to coating_mass

// Exchange terms for the fluid (orchestrator -> fluid)
// drag_coefficient and velocity (above) are sent for the implicit momentum exchange
inline constexpr const char* transfer_coefficient = "transfer_coefficient";
// [kg/s] per unit precursor mass fraction: parcel removes transfer_coefficient * Y per second

// Fluid results per particle (fluid -> orchestrator)
inline constexpr const char* precursor_removed = "precursor_removed";  // [kg] over the interval

// Number of components of a field (1 for scalars); 0 for an unknown name.
unsigned components(const std::string& name);
// The same, 1 for an unknown name (a field a plugin model adds: stored as a scalar).
inline unsigned componentsOrOne(const std::string& name) {
  const unsigned c = components(name);
  return c == 0 ? 1U : c;
}
// SI unit of a field as written in particles.h5 ("m", "m/s", "kg", "-" ...); "" if unknown.
const char* units(const std::string& name);
// What a field means, one line (recorded with it in particles.h5); "" for an unknown name.
const char* description(const std::string& name);
// Every known field name.
const std::vector<std::string>& all();

}  // namespace cosim::field
