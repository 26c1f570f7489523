// Small vector helpers and parameter readers shared by the coating-zone shapes.
// Points ON a shape's boundary are inside (closed sets); shapes compare squared distances so a
// boundary point given exactly is classified exactly.
#pragma once

#include <array>
#include <string>

#include "cosim/models/parameters.h"

namespace cosim::models {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 minus(const double* x, const Vec3& b) {
  return {x[0] - b[0], x[1] - b[1], x[2] - b[2]};
}

Vec3 readPoint(const Parameters& p, const std::string& key);      // 3 finite numbers
Vec3 readDirection(const Parameters& p, const std::string& key);  // non-zero; returned unit

// Axial coordinate s in [0, length] and squared radial distance of x from the axis line.
struct AxialPosition {
  double s;
  double r2;
};
AxialPosition axialPosition(const double* x, const Vec3& base, const Vec3& unit_axis);

}  // namespace cosim::models
