#include "cosim/models/zone/geometry.h"

#include <cmath>

namespace cosim::models {

Vec3 readPoint(const Parameters& p, const std::string& key) {
  const auto v = p.list(key, 3);
  for (double x : v) {
    if (!std::isfinite(x)) {
      throw ModelError(p.owner() + ": parameter '" + key + "' must be 3 finite numbers [m]");
    }
  }
  return {v[0], v[1], v[2]};
}

Vec3 readDirection(const Parameters& p, const std::string& key) {
  Vec3 a = readPoint(p, key);
  const double n = std::sqrt(dot(a, a));
  if (!(n > 0.0)) {
    throw ModelError(p.owner() + ": parameter '" + key +
                     "' is the zero vector; give the direction of the axis, e.g. [0, 0, 1]");
  }
  if (n != 1.0) {
    for (double& x : a) x /= n;
  }
  return a;
}

AxialPosition axialPosition(const double* x, const Vec3& base, const Vec3& unit_axis) {
  const Vec3 r = minus(x, base);
  const double s = dot(r, unit_axis);
  const Vec3 radial = {r[0] - s * unit_axis[0], r[1] - s * unit_axis[1], r[2] - s * unit_axis[2]};
  return {s, dot(radial, radial)};
}

}  // namespace cosim::models
