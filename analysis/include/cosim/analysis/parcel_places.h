// Where a group of parcels sits in the bed compared with the others, from the particle
// snapshots: height (z) and distance from the vertical axis through the centre of the bed at the
// start (mean x, y of the first snapshot), each averaged over the snapshots per parcel and then
// over the group, and at the start. The report uses it for the parcels that never reached the
// coating zone (docs/analysis.md section 10).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_set>

#include "cosim/analysis/particle_file.h"

namespace cosim::analysis {

struct PlaceOfGroup {
  std::size_t parcels = 0;
  double mean_height = std::numeric_limits<double>::quiet_NaN();   // [m] time average
  double mean_radius = std::numeric_limits<double>::quiet_NaN();   // [m] time average
  double start_height = std::numeric_limits<double>::quiet_NaN();  // [m] first snapshot
  double start_radius = std::numeric_limits<double>::quiet_NaN();  // [m] first snapshot
};

struct ParcelPlaces {
  bool valid = false;
  std::string problem;            // why not valid
  double axis_x = 0, axis_y = 0;  // [m]
  std::size_t snapshots = 0;
  PlaceOfGroup group;   // the parcels asked about
  PlaceOfGroup others;  // every other parcel
};

ParcelPlaces placesOf(const ParticleFile& file, const std::unordered_set<std::int64_t>& group);

}  // namespace cosim::analysis
