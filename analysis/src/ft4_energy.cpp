#include "cosim/analysis/ft4_energy.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {
namespace {

// The scene writes the fifth column since the resume fix; files of earlier runs have four.
const char* kHeader = "time_s,height_m,force_N,torque_Nm,averaged";
const char* kHeaderWithoutAveraged = "time_s,height_m,force_N,torque_Nm";

std::vector<std::string> splitComma(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double parseNumber(const std::string& text, const std::filesystem::path& file, int line,
                   const char* column) {
  std::string t = text;
  t.erase(0, t.find_first_not_of(" \t\r"));
  t.erase(t.find_last_not_of(" \t\r") + 1);
  double v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
    throw InputError(fmt::format("{}:{}: column {}: {} is not a finite number", file.string(), line,
                                 column, quotedCell(text)));
  return v;
}

}  // namespace

std::vector<BladeRow> readBladeRows(const std::filesystem::path& csv,
                                    std::vector<double>* cut_windows) {
  std::ifstream in(csv);
  if (!in)
    throw InputError(csv.string() +
                     ": cannot be read (a run of scenarios/ft4-rheometer writes it into "
                     "RUN/particles/; is this such a run?)");
  std::vector<BladeRow> rows;
  std::string line;
  int n = 0;
  std::size_t columns = 0;  // 0 until a header line was read
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line == kHeader || line == kHeaderWithoutAveraged) {
      columns = line == kHeader ? 5 : 4;
      continue;
    }
    if (columns == 0)
      throw InputError(
          fmt::format("{}:{}: expected the header line '{}' first", csv.string(), n, kHeader));
    const auto cells = splitComma(line);
    if (cells.size() != columns)
      throw InputError(fmt::format("{}:{}: expected {} columns ({}), found {}", csv.string(), n,
                                   columns, columns == 5 ? kHeader : kHeaderWithoutAveraged,
                                   cells.size()));
    BladeRow r{parseNumber(cells[0], csv, n, "time_s"), parseNumber(cells[1], csv, n, "height_m"),
               parseNumber(cells[2], csv, n, "force_N"),
               parseNumber(cells[3], csv, n, "torque_Nm")};
    // a resumed run writes again from its checkpoint: its rows replace the stopped run's
    while (!rows.empty() && rows.back().time_s >= r.time_s) rows.pop_back();
    if (cut_windows != nullptr)
      while (!cut_windows->empty() && cut_windows->back() >= r.time_s) cut_windows->pop_back();
    // LIGGGHTS' fix ave/time averages whole windows only: the window in which a run resumed
    // has no average (all columns 0, averaged 0); the row carries no measurement
    if (columns == 5 && parseNumber(cells[4], csv, n, "averaged") < 0.5) {
      if (cut_windows != nullptr) cut_windows->push_back(r.time_s);
      continue;
    }
    rows.push_back(r);
  }
  if (columns == 0) throw InputError(csv.string() + ": empty (no header '" + kHeader + "')");
  return rows;
}

double EnergyProfile::lowest_m() const {
  double h = INFINITY;
  for (const auto& p : points) h = std::min(h, p.height_m);
  return h;
}

double EnergyProfile::highest_m() const {
  double h = -INFINITY;
  for (const auto& p : points) h = std::max(h, p.height_m);
  return h;
}

double EnergyProfile::between(double h_low, double h_high) const {
  if (points.size() < 2 || h_low > h_high || h_low < lowest_m() - 1e-12 ||
      h_high > highest_m() + 1e-12)
    throw std::invalid_argument(fmt::format(
        "the blade's simulated descent covers heights {:.6g} .. {:.6g} m, not the requested "
        "{:.6g} .. {:.6g} m",
        points.empty() ? NAN : lowest_m(), points.empty() ? NAN : highest_m(), h_low, h_high));
  // cumulative energy at height h: heights fall monotonically (flowEnergy checks it)
  auto at = [&](double h) {
    for (std::size_t i = 1; i < points.size(); ++i) {
      const auto& a = points[i - 1];
      const auto& b = points[i];
      if (h <= a.height_m && h >= b.height_m && a.height_m > b.height_m)
        return a.energy_J +
               (b.energy_J - a.energy_J) * (a.height_m - h) / (a.height_m - b.height_m);
    }
    return h >= points.front().height_m ? points.front().energy_J : points.back().energy_J;
  };
  return at(h_low) - at(h_high);
}

EnergyProfile flowEnergy(const std::vector<BladeRow>& rows, double blade_radius_m,
                         double helix_deg) {
  if (!(blade_radius_m > 0))
    throw std::invalid_argument(fmt::format("blade radius must be > 0 m, got {}", blade_radius_m));
  if (!(helix_deg > 0 && helix_deg < 90))
    throw std::invalid_argument(
        fmt::format("helix angle must be between 0 and 90 degrees, got {}", helix_deg));
  EnergyProfile p;
  p.blade_radius_m = blade_radius_m;
  p.helix_deg = helix_deg;
  const double lever = blade_radius_m * std::tan(helix_deg * std::numbers::pi / 180.0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EnergyPoint e{rows[i].height_m,
                  rows[i].force_N,
                  rows[i].torque_Nm,
                  rows[i].torque_Nm / lever + rows[i].force_N,
                  0.0,
                  0.0};
    if (i > 0) {
      const auto& prev = p.points.back();
      const double dh = prev.height_m - e.height_m;
      if (dh < -1e-12) {
        // files written before the `averaged` column: the window a resume cut reads as a row
        // of height, force and torque exactly 0
        const auto& cut = rows[i - 1];
        const bool looks_cut = cut.height_m == 0 && cut.force_N == 0 && cut.torque_Nm == 0;
        throw std::invalid_argument(fmt::format(
            "the blade rises from {:.9g} m to {:.9g} m at t = {} s: the flow energy of Eq. 11 "
            "is that of a downward test{}",
            prev.height_m, e.height_m, rows[i].time_s,
            looks_cut ? fmt::format(" (the row at t = {} s has height, force and torque 0: the "
                                    "averaging window in which a run written without the "
                                    "'averaged' column resumed; delete that line of "
                                    "ft4_blade.csv)",
                                    rows[i - 1].time_s)
                      : std::string()));
      }
      e.energy_J =
          prev.energy_J + (dh > 0 ? 0.5 * (prev.gradient_J_per_m + e.gradient_J_per_m) * dh : 0.0);
      e.torque_energy_J =
          prev.torque_energy_J + (dh > 0 ? 0.5 * (prev.torque_Nm + e.torque_Nm) / lever * dh : 0.0);
    }
    p.points.push_back(e);
  }
  return p;
}

Ft4RunParameters readFt4RunParameters(const std::filesystem::path& run,
                                      const std::string& parameter) {
  const auto file = run / "scenario.resolved.yaml";
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(file.string());
  } catch (const std::exception& e) {
    throw InputError(file.string() + ": cannot be read as a run's resolved scene (" + e.what() +
                     "); is " + run.string() + " a run folder?");
  }
  auto get = [&](const std::string& name) {
    const auto node = doc["parameters"][name];
    if (!node || !node.IsScalar())
      throw InputError(file.string() + ": no parameter '" + name +
                       "' (a run of scenarios/ft4-rheometer has it)");
    try {
      return node.as<double>();
    } catch (const std::exception&) {
      throw InputError(file.string() + ": parameter '" + name + "' = '" + node.as<std::string>() +
                       "' is not a number");
    }
  };
  Ft4RunParameters p;
  p.blade_radius_m = get("blade_radius");
  p.helix_deg = get("helix_deg");
  if (!parameter.empty()) p.parameter = get(parameter);
  return p;
}

EnergyProfile runFlowEnergy(const std::filesystem::path& run) {
  const auto par = readFt4RunParameters(run);
  std::vector<double> cut;
  const auto rows = readBladeRows(run / "particles" / "ft4_blade.csv", &cut);
  try {
    auto profile = flowEnergy(rows, par.blade_radius_m, par.helix_deg);
    profile.cut_windows_s = std::move(cut);
    return profile;
  } catch (const std::invalid_argument& e) {
    throw InputError(run.string() + ": " + e.what());
  }
}

std::string energyProfileCsv(const EnergyProfile& profile) {
  std::string s = "height_m,force_N,torque_Nm,gradient_J_per_m,energy_J\n";
  for (const auto& p : profile.points)
    s += formatShortest(p.height_m) + "," + formatShortest(p.force_N) + "," +
         formatShortest(p.torque_Nm) + "," + formatShortest(p.gradient_J_per_m) + "," +
         formatShortest(p.energy_J) + "\n";
  return s;
}

}  // namespace cosim::analysis
