// Coating-zone membership exactly on and just around each shape's boundary (closed shapes:
// boundary points are inside). Boundary points are chosen exactly representable; "just
// outside" is the next double away from the shape.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cosim/models/registry.h"

namespace cosim::models {
namespace {

double up(double x) { return std::nextafter(x, INFINITY); }
double down(double x) { return std::nextafter(x, -INFINITY); }

bool in(const CoatingZone& z, double x, double y, double zc) {
  const double p[3] = {x, y, zc};
  return z.contains(p);
}

Parameters cylinderParams() {
  Parameters p("coating_zone");
  p.setList("base", {0.0, 0.0, 0.0});
  p.setList("axis", {0.0, 0.0, 2.0});  // normalised to (0, 0, 1)
  p.set("radius", 0.5);
  p.set("length", 1.0);
  return p;
}

TEST(CoatingZone, CylinderBoundaryIsExact) {
  auto z = Registry::instance().makeZone("cylinder", cylinderParams());
  EXPECT_TRUE(in(*z, 0.5, 0.0, 0.5));       // on the side
  EXPECT_FALSE(in(*z, up(0.5), 0.0, 0.5));  // just outside the side
  EXPECT_TRUE(in(*z, 0.0, -0.5, 0.5));
  EXPECT_FALSE(in(*z, 0.0, down(-0.5), 0.5));
  EXPECT_TRUE(in(*z, 0.3, 0.4, 0.0));  // on the bottom disc edge region (r = 0.5)
  EXPECT_TRUE(in(*z, 0.0, 0.0, 0.0));  // bottom
  EXPECT_FALSE(in(*z, 0.0, 0.0, down(0.0)));
  EXPECT_TRUE(in(*z, 0.0, 0.0, 1.0));  // top
  EXPECT_FALSE(in(*z, 0.0, 0.0, up(1.0)));
  EXPECT_TRUE(in(*z, 0.25, 0.25, 0.75));  // well inside
  EXPECT_FALSE(in(*z, 0.4, 0.4, 0.5));    // r = 0.566
}

TEST(CoatingZone, TiltedCylinderAroundItsBoundary) {
  Parameters p("coating_zone");
  p.setList("base", {1.0, 2.0, 3.0});
  p.setList("axis", {1.0, 1.0, 0.0});
  p.set("radius", 0.25);
  p.set("length", 2.0);
  auto z = Registry::instance().makeZone("cylinder", p);
  const double s = 1.0 / std::sqrt(2.0);
  // axial position 1 along (1,1,0)/sqrt2, radial offset along z (perpendicular to the axis)
  for (double f : {1.0 - 1e-12, 1.0 + 1e-12}) {
    EXPECT_EQ(in(*z, 1.0 + s, 2.0 + s, 3.0 + 0.25 * f), f < 1.0) << f;
  }
  EXPECT_TRUE(in(*z, 1.0 + 2.0 * s * (1 - 1e-12), 2.0 + 2.0 * s * (1 - 1e-12), 3.0));
  EXPECT_FALSE(in(*z, 1.0 + 2.0 * s * (1 + 1e-12), 2.0 + 2.0 * s * (1 + 1e-12), 3.0));
}

TEST(CoatingZone, ConeFrustumBoundaryIsExact) {
  Parameters p("coating_zone");
  p.setList("base", {0.0, 0.0, 0.0});
  p.setList("axis", {0.0, 0.0, 1.0});
  p.set("length", 1.0);
  p.set("base_radius", 0.5);
  p.set("top_radius", 0.25);
  auto z = Registry::instance().makeZone("cone_frustum", p);
  EXPECT_TRUE(in(*z, 0.5, 0.0, 0.0));  // base rim
  EXPECT_FALSE(in(*z, up(0.5), 0.0, 0.0));
  EXPECT_TRUE(in(*z, 0.375, 0.0, 0.5));  // R(0.5) = 0.375
  EXPECT_FALSE(in(*z, up(0.375), 0.0, 0.5));
  EXPECT_TRUE(in(*z, 0.0, 0.25, 1.0));  // top rim
  EXPECT_FALSE(in(*z, 0.0, up(0.25), 1.0));
  EXPECT_FALSE(in(*z, 0.0, 0.0, up(1.0)));
  EXPECT_FALSE(in(*z, 0.0, 0.0, down(0.0)));
  EXPECT_FALSE(in(*z, 0.45, 0.0, 0.5));  // inside the base radius but outside the slope
}

TEST(CoatingZone, BoxBoundaryIsExact) {
  Parameters p("coating_zone");
  p.setList("min", {-1.0, -1.0, 0.0});
  p.setList("max", {1.0, 1.0, 2.0});
  auto z = Registry::instance().makeZone("box", p);
  EXPECT_TRUE(in(*z, -1.0, -1.0, 0.0));
  EXPECT_TRUE(in(*z, 1.0, 1.0, 2.0));
  EXPECT_FALSE(in(*z, down(-1.0), 0.0, 1.0));
  EXPECT_FALSE(in(*z, up(1.0), 0.0, 1.0));
  EXPECT_FALSE(in(*z, 0.0, down(-1.0), 1.0));
  EXPECT_FALSE(in(*z, 0.0, up(1.0), 1.0));
  EXPECT_FALSE(in(*z, 0.0, 0.0, down(0.0)));
  EXPECT_FALSE(in(*z, 0.0, 0.0, up(2.0)));
}

TEST(CoatingZone, SphereBoundaryIsExact) {
  Parameters p("coating_zone");
  p.setList("center", {1.0, 1.0, 1.0});
  p.set("radius", 0.5);
  auto z = Registry::instance().makeZone("sphere", p);
  EXPECT_TRUE(in(*z, 1.5, 1.0, 1.0));
  EXPECT_FALSE(in(*z, up(1.5), 1.0, 1.0));
  EXPECT_TRUE(in(*z, 1.0, 0.5, 1.0));
  // 1 - nextafter(0.5, 0) rounds back to 0.5 (a translated point cannot resolve one ulp of
  // its own coordinate), so step out by 1e-15 here
  EXPECT_FALSE(in(*z, 1.0, 0.5 - 1e-15, 1.0));
  EXPECT_TRUE(in(*z, 1.3, 1.4, 1.0));  // 0.3^2 + 0.4^2 = 0.25 (to round-off: inside)
  EXPECT_FALSE(in(*z, 1.3, 1.41, 1.0));
}

TEST(CoatingZone, UnionIsInsideAnyPartAndNests) {
  Parameters cyl = cylinderParams();
  cyl.setText("shape", "cylinder");
  Parameters sph("part");
  sph.setText("shape", "sphere");
  sph.setList("center", {0.0, 0.0, 3.0});
  sph.set("radius", 0.5);
  Parameters inner("part");
  inner.setText("shape", "union");
  inner.setChild("parts", {sph});
  Parameters p("coating_zone");
  p.setChild("parts", {cyl, inner});
  auto z = Registry::instance().makeZone("union", p);
  EXPECT_TRUE(in(*z, 0.0, 0.0, 0.5));  // cylinder
  EXPECT_TRUE(in(*z, 0.0, 0.0, 3.5));  // sphere top
  EXPECT_FALSE(in(*z, 0.0, 0.0, up(3.5)));
  EXPECT_FALSE(in(*z, 0.0, 0.0, 2.0));  // between the two
  // batch mask: 1 inside, 0 outside
  const std::vector<double> pos = {0, 0, 0.5, 0, 0, 2.0, 0, 0, 3.0};
  ParcelBatch b;
  b.n = 3;
  b.position = pos.data();
  std::vector<double> mask(3, -1.0);
  z->mask(b, mask.data());
  EXPECT_EQ(mask, (std::vector<double>{1.0, 0.0, 1.0}));
  EXPECT_EQ(z->requiredFields(), std::vector<std::string>{"position"});
}

}  // namespace
}  // namespace cosim::models
