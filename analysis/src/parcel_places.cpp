#include "cosim/analysis/parcel_places.h"

#include <cmath>
#include <unordered_map>
#include <vector>

#include "cosim/link/fields.h"

namespace cosim::analysis {

namespace {
struct Sums {
  double z = 0, r = 0;
  std::size_t n = 0;
};
}  // namespace

ParcelPlaces placesOf(const ParticleFile& file, const std::unordered_set<std::int64_t>& group) {
  ParcelPlaces out;
  const auto& snaps = file.snapshots();
  if (!file.hasField(cosim::field::position)) {
    out.problem = file.path().string() + " has no position field";
    return out;
  }
  std::size_t first = 0;
  while (first < snaps.size() && snaps[first].count == 0) ++first;
  if (first == snaps.size()) {
    out.problem = file.path().string() + " holds no snapshot with parcels";
    return out;
  }
  {
    const auto x = file.read(first, cosim::field::position);
    const std::size_t n = x.size() / 3;
    for (std::size_t i = 0; i < n; ++i) {
      out.axis_x += x[3 * i];
      out.axis_y += x[3 * i + 1];
    }
    out.axis_x /= static_cast<double>(n);
    out.axis_y /= static_cast<double>(n);
  }
  std::unordered_map<std::int64_t, Sums> parcel;
  std::unordered_map<std::int64_t, std::pair<double, double>> at_start;
  for (std::size_t s = first; s < snaps.size(); ++s) {
    if (snaps[s].count == 0) continue;
    const auto ids = file.ids(s);
    const auto x = file.read(s, cosim::field::position);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const double dx = x[3 * i] - out.axis_x, dy = x[3 * i + 1] - out.axis_y;
      const double r = std::sqrt(dx * dx + dy * dy), z = x[3 * i + 2];
      auto& p = parcel[ids[i]];
      p.z += z;
      p.r += r;
      ++p.n;
      if (s == first) at_start[ids[i]] = {z, r};
    }
    ++out.snapshots;
  }
  Sums mean[2], start[2];
  for (const auto& [id, p] : parcel) {
    const int g = group.count(id) ? 0 : 1;
    mean[g].z += p.z / static_cast<double>(p.n);
    mean[g].r += p.r / static_cast<double>(p.n);
    ++mean[g].n;
    if (auto it = at_start.find(id); it != at_start.end()) {
      start[g].z += it->second.first;
      start[g].r += it->second.second;
      ++start[g].n;
    }
  }
  PlaceOfGroup* places[2] = {&out.group, &out.others};
  for (int g = 0; g < 2; ++g) {
    PlaceOfGroup& o = *places[g];
    o.parcels = mean[g].n;
    if (mean[g].n > 0) {
      o.mean_height = mean[g].z / static_cast<double>(mean[g].n);
      o.mean_radius = mean[g].r / static_cast<double>(mean[g].n);
    }
    if (start[g].n > 0) {
      o.start_height = start[g].z / static_cast<double>(start[g].n);
      o.start_radius = start[g].r / static_cast<double>(start[g].n);
    }
  }
  out.valid = true;
  return out;
}

}  // namespace cosim::analysis
