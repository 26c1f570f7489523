// The voidage stays smooth when a parcel crosses a face of cells only 2.7 diameters wide
// (4 mm cells, 1.5 mm parcel): moving it in 0.05 mm steps from wholly left to wholly right of a
// face, a cell's voidage changes by a few satellites' shares at most (the largest share of the
// 27 is 7 %; two may cross within one step), < 15 % of the parcel's volume fraction per step,
// and by exactly the parcel's volume fraction in total. With the whole parcel at its centre
// (voidage_divisions 1) the same crossing is one jump of 100 %; an axis-aligned 3x3x3 pattern
// would cross a whole layer (48 %) at once, hence the rotated pattern.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "foam_harness.h"

namespace cosim::test {
namespace {

struct Crossing {
  double largestStep = 0;
  double total = 0;
};

Crossing cross(int divisions) {
  FoamRunConfig cfg;
  cfg.substitute = {{"inlet_velocity", "0"},
                    {"inlet_precursor", "0"},
                    {"write_steps", "100000"},
                    {"wall_U", "slip"}};
  cfg.options_yaml = "{min_voidage: 0.05, voidage_divisions: " + std::to_string(divisions) + "}";
  cfg.send = {"voidage"};
  cfg.receive = {"position", "radius"};
  FoamRun run(cfg);
  // Parcel 1 (r = 0.75 mm) crosses the face x = 8 mm of the cells at y, z = 10, 42 mm.
  // Parcel 2 is a probe of negligible volume at the left cell's centre: its sampled voidage is
  // that cell's.
  auto p = makeParticles({0, 0.010, 0.042, 0.006, 0.010, 0.042}, 0);
  p.field("radius") = {0.75e-3, 1e-9};
  Crossing c;
  double previous = -1, first = 0;
  for (int k = 0; k <= 60; ++k) {
    p.field("position")[0] = 0.0065 + 0.05e-3 * k;  // 6.5 mm (wholly left) .. 9.5 mm (right)
    const double eps = run.sample(p).at.get("voidage")[1];
    if (previous >= 0) c.largestStep = std::max(c.largestStep, std::abs(eps - previous));
    if (k == 0) first = eps;
    previous = eps;
  }
  c.total = previous - first;
  EXPECT_EQ(run.shutdown(), 0);
  return c;
}

TEST(OpenFoamVoidage, SmoothWhenAParcelCrossesAFace) {
  const double r = 0.75e-3, cell = 0.004;
  const double fraction = 4.0 / 3.0 * std::numbers::pi * r * r * r / (cell * cell * cell);
  const Crossing smooth = cross(3);
  EXPECT_NEAR(smooth.total, fraction, 1e-12);
  EXPECT_LT(smooth.largestStep, 0.15 * fraction);
  const Crossing centre = cross(1);
  EXPECT_NEAR(centre.total, fraction, 1e-12);
  EXPECT_NEAR(centre.largestStep, fraction, 1e-12);
  std::printf(
      "parcel fraction %.4f: largest step %.2f %% of it with 27 satellites, %.0f %% "
      "without\n",
      fraction, 100 * smooth.largestStep / fraction, 100 * centre.largestStep / fraction);
}

}  // namespace
}  // namespace cosim::test
