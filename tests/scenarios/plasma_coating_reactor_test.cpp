// The paper's round coating reactor in miniature (scenarios/plasma-coating-reactor/tiny.yaml) with
// the real solvers: the O-grid and its patches, the round nozzle's feed, the grains' count and
// walls, coating only in the zone, and the precursor balance, each against a hand count.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>

#include "cosim/analysis/zone_pass_file.h"
#include "cosim/link/fields.h"
#include "coupler.h"
#include "scenario.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {
std::string readText(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// nFaces of each patch in constant/polyMesh/boundary
std::map<std::string, int> patchFaces(const fs::path& boundary) {
  std::map<std::string, int> out;
  const std::string text = readText(boundary);
  const std::regex entry(R"((\w+)\s*\{[^}]*?nFaces\s+(\d+);)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry);
       it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = std::stoi((*it)[2]);
  return out;
}
}  // namespace

TEST(PlasmaCoatingReactorTiny, MeshNozzleGrainsAndZoneAsCountedByHand) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-reactor-tiny-" + std::to_string(getpid()));
  fs::remove_all(out);
  Scenario sc =
      loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-reactor/tiny.yaml");
  RunOptions o;
  o.quiet = true;
  o.output = out;
  RunResult r = Coupler(std::move(sc), o).run();
  ASSERT_EQ(r.exit_code, 0) << r.message;

  // The O-grid of tiny.yaml (cell 3 mm, R 18 mm, nozzle 7.9 mm with 4 cells on each quarter of
  // its circle, protruding 3 mm, H 45 mm): the square around the nozzle has half-width b = 2 cells
  // = 6 mm; the vessel's core s = b + 1 cell = 9 mm (round((0.55 R - b) / cell) = round(1.3));
  // 3 cells from it to the wall (9 mm); one cell from the nozzle's circle to b and from its core to
  // its circle; 1 layer below the nozzle's exit, 14 above. So 6 faces on each quarter of the wall
  // and per layer: 4 x 6 x 3 outer + (6^2 - 4^2) core + 4 x 4 x 1 around the nozzle = 108 cells,
  // and 4 x 4 + 4 x 4 x 1 = 32 in the nozzle's column above its exit.
  const std::string owner = readText(r.folder / "fluid/constant/polyMesh/owner");
  EXPECT_NE(owner.find("nCells:" + std::to_string(108 * 15 + 32 * 14)), std::string::npos)
      << owner.substr(0, 600);
  const auto faces = patchFaces(r.folder / "fluid/constant/polyMesh/boundary");
  EXPECT_EQ(faces.at("distributor"), 108);   // the plate around the nozzle: one layer's cells
  EXPECT_EQ(faces.at("nozzle"), 32);         // the nozzle's exit
  EXPECT_EQ(faces.at("nozzleWall"), 16);     // its side: 16 faces round, one layer high
  EXPECT_EQ(faces.at("walls"), 4 * 6 * 15);  // 24 faces round, 15 layers
  EXPECT_EQ(faces.at("outlet"), 108 + 32);

  // The nozzle: a 16-sided polygon of the area of the 7.9 mm round nozzle, fed at u_nozzle with
  // Y = 0.011 of N2 at the outlet's pressure (rho = p M / (R T)); the gas at the exit is a few
  // hundred Pa above it, a few per mille denser. A square nozzle of 8 mm would feed 31 % more,
  // the polygon inscribed in the 7.9 mm circle 2.6 % less.
  const double rho = 1e5 * 0.0280134 / (8.314462618 * 300.0);
  const double area = std::numbers::pi * 0.0079 * 0.0079 / 4.0;
  const double fed = 0.011 * rho * 3.2 * area * 0.04;
  EXPECT_NEAR(r.totals.at("precursor_in_kg"), fed, 0.01 * fed);

  // The grains: 6.2 g of 1.5 mm parcels of 1750 kg/m3 (3.0925e-6 kg each) = 2005 parcels, none
  // lost; each inside the round wall (R cos(pi / 24): the polygon's faces) and none inside the
  // nozzle (its polygon's faces at 4.0014 mm cos(pi / 16) from the axis, up to 3 mm).
  const double parcel = 1750.0 * std::numbers::pi / 6.0 * std::pow(1.5e-3, 3);
  const auto n = static_cast<std::size_t>(std::llround(0.0062 / parcel));
  ASSERT_EQ(n, 2005u);
  ASSERT_EQ(r.final_state.size(), n);
  const auto& x = r.final_state.get(cosim::field::position);
  const double wall = 0.018 * std::cos(std::numbers::pi / 24.0);
  const double nozzle = 0.0040014 * std::cos(std::numbers::pi / 16.0);
  const double overlap = 0.05 * 0.75e-3;  // Hertz overlap at these loads: far below 5 % of a radius
  for (std::size_t i = 0; i < n; ++i) {
    const double rad = std::hypot(x[3 * i], x[3 * i + 1]);
    const double z = x[3 * i + 2];
    EXPECT_LE(rad + 0.75e-3, wall + overlap) << "parcel " << r.final_state.ids[i];
    if (z < 0.003) EXPECT_GE(rad, nozzle + 0.75e-3 - overlap) << "parcel " << r.final_state.ids[i];
    EXPECT_GE(z, 0.75e-3 - overlap);
  }

  // Coating only in the zone: each parcel's coating is the sum of its passes, a parcel without a
  // pass has none; and the gas's balance closes (in = out + held + removed).
  const auto passes = cosim::analysis::readZonePasses(r.folder / cosim::analysis::kZonePassesFile);
  ASSERT_FALSE(passes.empty()) << "no parcel entered the coating zone above the nozzle";
  std::map<std::int64_t, double> inPasses;
  for (const auto& p : passes) inPasses[p.parcel_id] += p.coating;
  const auto& m = r.final_state.get(cosim::field::coating_mass);
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = inPasses.find(r.final_state.ids[i]);
    const double expected = it == inPasses.end() ? 0.0 : it->second;
    EXPECT_NEAR(m[i], expected, 1e-12 * std::max(m[i], 1e-30)) << r.final_state.ids[i];
  }
  const double in = r.totals.at("precursor_in_kg");
  const double balance = in - r.totals.at("precursor_out_kg") - r.totals.at("precursor_held_kg");
  EXPECT_LT(std::fabs(balance - r.totals.at("precursor_removed_kg")), 1e-4 * in);
  EXPECT_GT(r.totals.at("precursor_removed_kg"), 0.0);
  fs::remove_all(out);
}
