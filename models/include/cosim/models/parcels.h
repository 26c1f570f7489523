// What a coupling model sees: a batch of parcels as contiguous arrays, and the scene constants.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace cosim::models {

// Scene-wide constants every law may use.
struct SceneConstants {
  double cg = 1.0;            // coarse-graining factor: parcel diameter = cg * real diameter
  double min_voidage = 0.35;  // voidage is clamped to [min_voidage, 1] before any law sees it
  double gravity[3] = {0.0, 0.0, -9.81};
  double schmidt = 1.0;  // Sc = mu / (rho D)
};

// Per-parcel inputs. Vectors are interleaved x,y,z (3n doubles). A pointer is null when the
// scene does not carry that field (a model must declare the fields it needs, see Model).
struct ParcelBatch {
  std::size_t n = 0;
  std::size_t first = 0;  // the index of the batch's first parcel among all (for messages)
  const double* position = nullptr;            // [m] 3n
  const double* velocity = nullptr;            // [m/s] 3n
  const double* radius = nullptr;              // [m] n, parcel (simulated) radius
  const double* fluid_velocity = nullptr;      // [m/s] 3n
  const double* voidage = nullptr;             // [-] n
  const double* fluid_density = nullptr;       // [kg/m3] n
  const double* fluid_viscosity = nullptr;     // [Pa s] n
  const double* pressure_gradient = nullptr;   // [Pa/m] 3n
  const double* precursor_fraction = nullptr;  // [-] n
  const double* cell_size = nullptr;           // [m] n
  // Optional, n flags: nonzero = the parcel is in no fluid cell (the fluid reported it in
  // lost_ids and sent zero samples). Laws give it 0 (no drag, no force, no transfer) and do
  // not check its fluid samples. Null = no parcel is lost.
  const char* lost = nullptr;
  // Optional, 3n [N]: the part of each parcel's own force its cell's gas has answered so far
  // (WakeBuildup, cosim/models/drag/wake_buildup.h); read by undisturbed_velocity
  // 'self_disturbance_transient' only. Not a wire field: the coupler fills it.
  const double* built_up_force = nullptr;

  // Kept by checkInputs: the arrays it has already found valid in this batch (by field), so
  // that the next law reading the same field does not scan it again. A copy of the batch that
  // points a field at another array (the undisturbed gas velocity) has that one scanned.
  mutable std::array<const double*, 12> checked{};
  mutable const char* checked_lost = nullptr;
  mutable std::size_t checked_n = 0;

  bool isLost(std::size_t i) const { return lost != nullptr && lost[i] != 0; }
};

// Per-parcel arrays owned together (tests, benchmarks); view() is a ParcelBatch over them, an
// empty array being a field the batch does not carry.
struct ParcelArrays {
  std::vector<double> position, velocity, radius, fluid_velocity, voidage, fluid_density,
      fluid_viscosity, pressure_gradient, precursor_fraction, cell_size;

  ParcelBatch view() const;
  std::size_t size() const { return radius.size(); }
};

// The one map between the per-particle field names of the wire (cosim/link/fields.h) and the
// members of ParcelBatch and ParcelArrays.
struct ParcelField {
  const char* name;
  const double* ParcelBatch::*batch;
  std::vector<double> ParcelArrays::*arrays;
};
inline constexpr ParcelField kParcelFields[] = {
    {"position", &ParcelBatch::position, &ParcelArrays::position},
    {"velocity", &ParcelBatch::velocity, &ParcelArrays::velocity},
    {"radius", &ParcelBatch::radius, &ParcelArrays::radius},
    {"fluid_velocity", &ParcelBatch::fluid_velocity, &ParcelArrays::fluid_velocity},
    {"voidage", &ParcelBatch::voidage, &ParcelArrays::voidage},
    {"fluid_density", &ParcelBatch::fluid_density, &ParcelArrays::fluid_density},
    {"fluid_viscosity", &ParcelBatch::fluid_viscosity, &ParcelArrays::fluid_viscosity},
    {"pressure_gradient", &ParcelBatch::pressure_gradient, &ParcelArrays::pressure_gradient},
    {"precursor_fraction", &ParcelBatch::precursor_fraction, &ParcelArrays::precursor_fraction},
    {"cell_size", &ParcelBatch::cell_size, &ParcelArrays::cell_size},
};

// A batch of n parcels over the arrays lookup(name) returns (const double*, nullptr for a field
// the scene does not carry), e.g. the orchestrator's per-particle data received from the
// participants.
template <class Lookup>
ParcelBatch bindParcelBatch(std::size_t n, Lookup&& lookup) {
  ParcelBatch b;
  b.n = n;
  for (const auto& f : kParcelFields) b.*f.batch = lookup(f.name);
  return b;
}

}  // namespace cosim::models
