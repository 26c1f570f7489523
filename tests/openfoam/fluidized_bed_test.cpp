// The first real coupled scene (scenarios/fluidized-bed): OpenFOAM (cosimFoam) and LIGGGHTS as
// separate processes through the orchestrator. Above minimum fluidization the time-averaged bed
// pressure drop equals (bed weight - buoyancy)/area (+ the gas column) within 3 %; below it the
// bed stays put. Results land in OpenFOAM time folders and particle files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "coupler.h"
#include "scenario.h"

namespace {

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

const fs::path kScene = fs::path(COSIM_SOURCE_DIR) / "scenarios/fluidized-bed/scenario.yaml";

// Independent of the scene's own expressions: 1000 parcels of 1.5 mm at 1750 kg/m3 in N2
// (1.1231 kg/m3) over a 16 x 16 mm section, plus the 64 mm gas column (the scene's inlet is
// fixedFluxPressure, so the inlet face pressure is extrapolated to the distributor).
double expectedPressureDrop() {
  const double pi = 3.14159265358979323846;
  const double dp = 1.5e-3, W = 0.016, rho_p = 1750, rho_g = 1.1231, g = 9.81;
  const double weight = 1000 * pi / 6 * dp * dp * dp * (rho_p - rho_g) * g / (W * W);
  return weight + rho_g * g * 0.064;
}

RunResult runScene(const std::vector<std::string>& sets, const std::string& tag,
                   std::map<std::int64_t, std::array<double, 3>>* start = nullptr,
                   const fs::path& scene = kScene) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-fluidized-" + tag + "-" + std::to_string(getpid()));
  fs::remove_all(out);
  RunOptions o;
  o.quiet = true;
  o.output = out;
  Coupler c(loadScenario(scene, sets), o);
  // Reference positions once the gas has been on for 0.02 s (the bed has taken its flow)
  bool first = true;
  c.on_step = [&](double t, const cosim::link::ParticleData& s) {
    if (!first || start == nullptr || t < 0.02) return;
    first = false;
    const auto& x = s.get("position");
    for (std::size_t i = 0; i < s.size(); ++i)
      (*start)[s.ids[i]] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  };
  return c.run();
}

double observable(const RunResult& r, const std::string& name) {
  for (const auto& o : r.observables) {
    if (o.name == name) return o.value;
  }
  ADD_FAILURE() << "no observable " << name;
  return NAN;
}

TEST(FluidizedBed, AboveMinimumFluidizationPressureDropCarriesTheBed) {
  const RunResult r = runScene({}, "above");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  const double dp = observable(r, "bed_pressure_drop");
  const double expected = expectedPressureDrop();
  EXPECT_NEAR(dp, expected, 0.03 * expected);
  std::printf(
      "time-averaged pressure drop %.2f Pa, (weight - buoyancy)/area + gas %.2f Pa (%.2f %%)\n", dp,
      expected, 100 * (dp - expected) / expected);
  // Results where a user looks for them
  EXPECT_TRUE(fs::exists(r.folder / "fluid" / "0.1" / "voidage"));
  EXPECT_TRUE(fs::exists(r.folder / "fluid" / "0.3" / "U"));
  EXPECT_TRUE(fs::exists(r.folder / "particles.h5"));
  fs::remove_all(r.folder);
}

TEST(FluidizedBed, BelowMinimumFluidizationTheBedStaysPut) {
  std::map<std::int64_t, std::array<double, 3>> start;
  const RunResult r = runScene({"u0=0.02", "end_time=0.1", "average_after=0.05"}, "below", &start);
  ASSERT_EQ(r.exit_code, 0) << r.message;
  ASSERT_EQ(start.size(), 1000u);
  const auto& x = r.final_state.get("position");
  std::vector<double> d;
  double sum = 0;
  for (std::size_t i = 0; i < r.final_state.size(); ++i) {
    const auto& s = start.at(r.final_state.ids[i]);
    d.push_back(std::hypot(x[3 * i] - s[0], x[3 * i + 1] - s[1], x[3 * i + 2] - s[2]));
    sum += d.back();
  }
  std::sort(d.begin(), d.end());
  const double mean = sum / static_cast<double>(d.size());
  const double p99 = d[d.size() * 99 / 100], moved = d.back();
  // Grains settle by small fractions of their diameter (1.5 mm): a surface grain may roll by
  // half a diameter, none is carried
  EXPECT_LT(mean, 0.02e-3) << "grains moved " << mean << " m on average in a bed below u_mf";
  EXPECT_LT(p99, 0.1e-3) << "1 % of the grains moved more than " << p99 << " m";
  EXPECT_LT(moved, 1.5e-3) << "a grain moved " << moved << " m in a bed below u_mf";
  // The gas passes through a fixed bed: it carries only part of the weight
  EXPECT_LT(observable(r, "bed_pressure_drop"), 0.8 * expectedPressureDrop());
  std::printf(
      "grain displacement mean %.3g m, 99 %% below %.3g m, largest %.3g m; pressure drop %.2f Pa\n",
      mean, p99, moved, observable(r, "bed_pressure_drop"));
  fs::remove_all(r.folder);
}

TEST(FluidizedBed, DecomposedFluidIsOneParticipant) {
  // participants.fluid.mpi = 2: the orchestrator starts `mpirun -np 2 cosimFoam`, which runs
  // decomposed and talks to it as one participant; the fields land in processor*/ folders.
  const RunResult r = runScene(
      {"participants.fluid.mpi=2", "u0=0.02", "end_time=0.05", "average_after=0.02"}, "mpi");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  for (const char* proc : {"processor0", "processor1"}) {
    EXPECT_TRUE(fs::exists(r.folder / "fluid" / proc / "0.05" / "voidage")) << proc;
    EXPECT_TRUE(fs::exists(r.folder / "fluid" / proc / "0.05" / "p")) << proc;
  }
  EXPECT_EQ(r.final_state.size(), 1000u);
  const double dp = observable(r, "bed_pressure_drop");
  EXPECT_GT(dp, 0.1 * expectedPressureDrop());
  EXPECT_LT(dp, 0.8 * expectedPressureDrop());
  fs::remove_all(r.folder);
}

// Largest |U| of an OpenFOAM volVectorField file (internalField, ascii)
double largestSpeed(const fs::path& file) {
  std::ifstream in(file);
  std::string word;
  while (in >> word && word != "internalField") {
  }
  in >> word;
  if (word == "uniform") {
    char paren = 0;
    double x = 0, y = 0, z = 0;
    in >> paren >> x >> y >> z;
    return std::hypot(x, y, z);
  }
  std::size_t n = 0;
  in >> word >> n;  // List<vector> n
  std::string text;
  std::getline(in, text, ';');
  for (char& ch : text) {
    if (ch == '(' || ch == ')') ch = ' ';
  }
  std::istringstream values(text);
  double worst = 0, x = 0, y = 0, z = 0;
  std::size_t read = 0;
  while (values >> x >> y >> z) {
    worst = std::max(worst, std::hypot(x, y, z));
    ++read;
  }
  EXPECT_EQ(read, n) << "could not read " << file;
  return worst;
}

TEST(FluidizedBed, RoundColumnOnAnOGridCarriesTheBed) {
  const RunResult r =
      runScene({}, "cylinder", nullptr,
               fs::path(COSIM_SOURCE_DIR) / "scenarios/fluidized-cylinder/scenario.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.message;
  // Independent of the scene's expressions: 1000 parcels of 3 mm at 1750 kg/m3 in N2
  // (1.1231 kg/m3) over the O-grid's cross-section, the 16-sided polygon inscribed in the
  // 25 mm circle (area 8 R^2 sin(pi/8), 2.5 % less than the circle), plus the 80 mm gas column
  const double pi = 3.14159265358979323846;
  const double dp = 3e-3, R = 0.025, rho_p = 1750, rho_g = 1.1231, g = 9.81;
  const double area = 8 * R * R * std::sin(pi / 8);
  const double expected =
      1000 * pi / 6 * dp * dp * dp * (rho_p - rho_g) * g / area + rho_g * g * 0.08;
  const double drop = observable(r, "bed_pressure_drop");
  const double speed = largestSpeed(r.folder / "fluid" / "0.3" / "U");
  std::printf(
      "O-grid column: time-averaged pressure drop %.2f Pa, (weight - buoyancy)/area + gas "
      "%.2f Pa (%.2f %%); largest gas speed at the end %.3f m/s\n",
      drop, expected, 100 * (drop - expected) / expected, speed);
  EXPECT_NEAR(drop, expected, 0.025 * expected);
  // Bubbling at 0.15 m/s: jets of a few times the superficial velocity, nothing like the
  // metres per second a wrong cell velocity produced within one step
  EXPECT_LT(speed, 1.5);
  fs::remove_all(r.folder);
}

}  // namespace
