// `cosim piv` and `cosim piv-compare` (piv_command.h).
#include "cosim/analysis/piv_command.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/piv_compare.h"
#include "cosim/analysis/piv_field.h"
#include "cosim/analysis/report.h"
#include "cosim/util/errors.h"
#include "cosim/util/format.h"

namespace cosim::analysis {

namespace {
namespace fs = std::filesystem;

// The numeric parameters of the scene a run was run with (empty without the file).
std::map<std::string, double> sceneParameters(const fs::path& run) {
  std::map<std::string, double> out;
  const auto file = run / "scenario.resolved.yaml";
  if (!fs::exists(file)) return out;
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw InputError(file.string() + ": cannot be read as YAML (" + e.what() +
                     "); give the PIV window on the command line instead");
  }
  const auto params = root["parameters"];
  if (!params || !params.IsMap()) return out;
  for (const auto& kv : params) {
    if (!kv.second.IsScalar()) continue;
    try {
      out[kv.first.as<std::string>()] = kv.second.as<double>();
    } catch (const YAML::Exception&) {
    }
  }
  return out;
}

double pick(const std::optional<double>& given, const std::map<std::string, double>& scene,
            const char* parameter, const char* option, const fs::path& run) {
  if (given) return *given;
  const auto it = scene.find(parameter);
  if (it != scene.end()) return it->second;
  if (!fs::exists(run / "scenario.resolved.yaml")) {
    throw InputError(fmt::format(
        "cosim piv: {} holds no scenario.resolved.yaml, so it is not a folder `cosim run` wrote "
        "(give the run's folder), or give {} on the command line",
        run.string(), option));
  }
  throw InputError(fmt::format(
      "cosim piv: {} gives no scene parameter '{}': give {} on the command line (or add the "
      "parameter to the scene)",
      (run / "scenario.resolved.yaml").string(), parameter, option));
}

// A table cell: a mean absolute error and its points, "-" without any.
std::string maeText(double mae, std::size_t points) {
  return points == 0 ? std::string("-") : fmt::format("{:.3f} ({})", mae, points);
}
std::string errorText(const MaeEntry& e) { return maeText(e.mae, e.points); }
std::string noiseText(const MaeEntry& e) { return maeText(e.noise_mae, e.noise_points); }

// A table row: the label and the three regions of a profile (or of all together) in one form.
template <class Regions>
std::string regionsRow(const std::string& label, const Regions& c,
                       std::string (*text)(const MaeEntry&)) {
  return fmt::format("  {:>12}  {:>14}  {:>14}  {:>14}", label, text(c.all), text(c.core),
                     text(c.sides));
}
}  // namespace

int runPivCommand(const PivCommandOptions& c, std::ostream& out) {
  const auto scene = sceneParameters(c.run);
  PivOptions o;
  o.wall_y = pick(c.wall_y, scene, kPivWallParameter, "--wall-y", c.run);
  o.x_min = pick(c.x_min, scene, kPivXMinParameter, "--x-min", c.run);
  o.x_max = pick(c.x_max, scene, kPivXMaxParameter, "--x-max", c.run);
  o.z_min = c.z_min.value_or(0.0);
  o.z_max = pick(c.z_max, scene, kPivZMaxParameter, "--z-max", c.run);
  if (c.from) {
    o.from = *c.from;
  } else if (scene.count(kPivDiscardParameter)) {
    o.from = scene.at(kPivDiscardParameter);
  }
  if (c.to) o.to = *c.to;
  o.depth = c.depth;
  o.cell = c.cell;
  o.heights = c.heights;
  o.blocks = c.blocks;
  const ParticleFile file(c.run / kParticlesFile);
  const PivResult r = pivField(file, o);
  const fs::path folder = c.output.empty() ? c.run / kPivFolder : c.output;
  claimOutputFiles({folder / "profiles.csv", folder / "grid.csv", folder / "piv.json",
                    folder / "piv.png", folder / "plot_piv.log"},
                   kProfilesHeader, "cosim piv -o");
  writePiv(r, o, folder);
  out << fmt::format(
      "cosim piv: {} snapshots from {} to {} s, parcels seen through the front wall y = {} m "
      "({}), {} samples on a grid of {} x {} cells of {} mm\n",
      r.snapshots, r.first_time, r.last_time, o.wall_y,
      o.depth ? "centre within " + util::fixed(1e3 * (*o.depth), 1) + " mm"
              : std::string("centre within its diameter"),
      r.samples, r.grid.nx, r.grid.nz, util::fixed(1e3 * (o.cell), 1));
  for (const auto& p : r.profiles) {
    out << fmt::format(
        "  profile at z = {} mm: x [mm] : vz [m/s] +- standard error ({} blocks) (samples)\n",
        util::fixed(1e3 * (p.height), 1), r.blocks);
    std::string line;
    for (std::size_t i = 0; i < p.x.size(); ++i) {
      line +=
          fmt::format("    {:>7} : {:>7} +- {:<6} ({})\n", util::fixed(1e3 * (p.x[i]), 1),
                      std::isfinite(p.vz[i]) ? fmt::format("{:.3f}", p.vz[i]) : "-",
                      std::isfinite(p.stderr_vz[i]) ? fmt::format("{:.3f}", p.stderr_vz[i]) : "-",
                      p.samples[i]);
    }
    out << line;
  }
  const double cut = static_cast<double>(r.grid.nx) * o.cell - (o.x_max - o.x_min);
  if (cut > 1e-9 * o.cell)
    out << fmt::format(
        "cosim piv: note: {} mm do not divide into cells of {} mm: the last column is cut at "
        "x = {} mm (its centre, {} mm, is not the centre of what it holds); a cell that divides "
        "the width avoids that\n",
        util::fixed(1e3 * (o.x_max - o.x_min), 1), util::fixed(1e3 * (o.cell), 1),
        util::fixed(1e3 * (o.x_max), 1), util::fixed(1e3 * (r.grid.xCentre(r.grid.nx - 1)), 1));
  out << "cosim piv: grid.csv, profiles.csv and piv.json in " << folder.string() << "\n";
  if (c.plots)
    out << "cosim piv: "
        << drawFigure("plot_piv.py", {"field", folder.string()}, folder / "piv.png",
                      folder / "plot_piv.log")
        << "\n";
  return 0;
}

int runPivCompareCommand(const PivCompareCommandOptions& c, std::ostream& out) {
  fs::path sim = c.simulated;
  if (fs::is_directory(sim)) {
    sim = sim / kPivFolder / "profiles.csv";
    if (!fs::exists(sim))
      throw InputError("cosim piv-compare: " + sim.string() + " does not exist: run `cosim piv " +
                       c.simulated.string() +
                       "` first (with --heights for the measured profiles' heights)");
  }
  for (const auto* label : {&c.simulated_label, &c.measured_label}) {
    const bool printable = std::all_of(label->begin(), label->end(),
                                       [](unsigned char ch) { return ch >= 0x20 && ch != 0x7f; });
    if (label->empty() || label->size() > 40 || !printable)
      throw InputError("cosim piv-compare: --labels: " + quotedCell(*label) +
                       ": expected two names of 1-40 printable characters, e.g. "
                       "--labels 'cg 5,cg 10'");
  }
  PivCompareOptions o;
  o.core_band = c.core_band;
  const auto simulated = readProfileCsv(sim);
  const auto measured = readProfileCsv(c.measured);
  const PivComparison r = comparePiv(simulated, measured, o);
  const std::string core_rule =
      c.core_band
          ? fmt::format("core: {} mm <= x <= {} mm", util::fixed(1e3 * (c.core_band->first), 1),
                        util::fixed(1e3 * (c.core_band->second), 1))
          : std::string("core: measured vz > 0, sides: vz <= 0");
  out << fmt::format("cosim piv-compare: {} against {} ({})\n", sim.string(), c.measured.string(),
                     core_rule);
  out << "  mean absolute error of vz [m/s] (points)\n";
  out << fmt::format("  {:>12}  {:>14}  {:>14}  {:>14}\n", "height [mm]", "all", "core", "sides");
  std::string csv = "height_m,region,points,mae_m_s,noise_mae_m_s\n";
  auto row = [&](const std::string& h, const MaeEntry& e, const char* region) {
    csv += fmt::format("{},{},{},{},{}\n", h, region, e.points,
                       e.points ? formatShortest(e.mae) : std::string(),
                       e.noise_points ? formatShortest(e.noise_mae) : std::string());
  };
  for (const auto& p : r.profiles) {
    out << regionsRow(util::fixed(1e3 * (p.height), 1), p, errorText);
    if (p.without_simulation)
      out << fmt::format("  ({} measured points beyond the simulated profile)",
                         p.without_simulation);
    out << "\n";
    const std::string h = formatShortest(p.height);
    row(h, p.all, "all");
    row(h, p.core, "core");
    row(h, p.sides, "sides");
  }
  out << regionsRow("all", r, errorText) << "\n";
  row("all", r.all, "all");
  row("all", r.core, "core");
  row("all", r.sides, "sides");
  if (r.all.noise_points > 0) {
    // the same table for the sampling noise alone: an error near it is not resolved
    out << "  from the sampling noise alone (standard errors of the profiles) [m/s] (points "
           "with one)\n";
    for (const auto& p : r.profiles)
      out << regionsRow(util::fixed(1e3 * (p.height), 1), p, noiseText) << "\n";
    out << regionsRow("all", r, noiseText) << "\n";
    out << "  an error no larger than about this is what two runs of the same model differ by\n";
  }
  const fs::path file = c.output.empty() ? sim.parent_path() / "comparison.csv" : c.output;
  auto png = file;
  png.replace_extension(".png");
  for (const auto& input : {sim, c.measured}) {
    std::error_code ec;
    for (const auto& written : {file, png})
      if (fs::equivalent(written, input, ec))
        throw InputError("cosim piv-compare: " + written.string() + " would overwrite the input " +
                         input.string() + ": give another -o");
  }
  const auto log = claimCsvWithPlot(file, csv, "cosim piv-compare -o").log;
  writeFileAtomically(file, csv);
  out << "cosim piv-compare: written " << file.string() << "\n";
  if (c.plots) {
    out << "cosim piv-compare: "
        << drawFigure("plot_piv.py",
                      {"compare", sim.string(), c.measured.string(), file.string(), png.string(),
                       c.simulated_label, c.measured_label},
                      png, log)
        << "\n";
  }
  return 0;
}

}  // namespace cosim::analysis
