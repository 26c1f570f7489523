#include "cosim/analysis/ft4_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/analysis/user_csv.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {
namespace {

double number(const std::string& t, const std::string& where, const std::string& column) {
  double v = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
    throw InputError(
        fmt::format("{}: column {}: {} is not a finite number", where, column, quotedCell(t)));
  return v;
}

bool startsWith(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

}  // namespace

double MeasuredEnergy::mean_J() const {
  double s = 0;
  for (double v : replicates_J) s += v;
  return replicates_J.empty() ? 0.0 : s / static_cast<double>(replicates_J.size());
}

double MeasuredEnergy::standard_error_J() const {
  const auto n = replicates_J.size();
  if (n < 2) return 0.0;
  const double m = mean_J();
  double ss = 0;
  for (double v : replicates_J) ss += (v - m) * (v - m);
  return std::sqrt(ss / static_cast<double>(n - 1) / static_cast<double>(n));
}

MeasuredEnergy readMeasuredEnergy(const std::filesystem::path& csv) {
  const std::string form =
      "expected a header with energy_J or energy_mJ (totals, one row per replicate), or "
      "height_m or height_mm and energy_J... / energy_mJ... columns (a cumulative profile, "
      "one column per replicate)";
  UserCsv in(csv,
             "a measured FT4 energy CSV: a header with energy_J or energy_mJ, or height_m / "
             "height_mm and energy columns");
  const auto& head = in.header();
  int height_col = -1;
  double height_scale = 1;
  std::vector<int> energy_cols;
  std::vector<double> energy_scale;
  for (int i = 0; i < static_cast<int>(head.size()); ++i) {
    const auto& h = head[i];
    if (h == "height_m" || h == "height_mm") {
      if (height_col >= 0) throw InputError(in.where() + ": two height columns; " + form);
      height_col = i;
      height_scale = h == "height_mm" ? 1e-3 : 1.0;
    } else if (startsWith(h, "energy_mJ")) {
      energy_cols.push_back(i);
      energy_scale.push_back(1e-3);
    } else if (startsWith(h, "energy_J")) {
      energy_cols.push_back(i);
      energy_scale.push_back(1.0);
    } else {
      throw InputError(fmt::format("{}: unknown column {}; {}", in.where(), quotedCell(h), form));
    }
  }
  if (energy_cols.empty()) throw InputError(in.where() + ": no energy column; " + form);
  if (height_col < 0 && energy_cols.size() != 1)
    throw InputError(in.where() + ": totals take one energy column (one row per replicate); " +
                     form);
  std::vector<std::vector<double>> rows;
  for (std::vector<std::string> c; in.next(c);) {
    const std::string where = in.where();
    std::vector<double> r;
    for (std::size_t i = 0; i < c.size(); ++i) r.push_back(number(c[i], where, head[i]));
    rows.push_back(r);
  }
  MeasuredEnergy m;
  if (height_col < 0) {
    for (const auto& r : rows) m.replicates_J.push_back(r[energy_cols[0]] * energy_scale[0]);
    if (m.replicates_J.empty()) throw InputError(csv.string() + ": no rows");
    for (std::size_t k = 0; k < m.replicates_J.size(); ++k)
      if (m.replicates_J[k] < 0)
        throw InputError(fmt::format(
            "{}: replicate {} (column {}): {} is negative; the flow energy is the work the blade "
            "does on the powder, >= 0 (check the sign convention of the export)",
            csv.string(), k + 1, head[energy_cols[0]], rows[k][energy_cols[0]]));
    return m;
  }
  if (rows.size() < 2) throw InputError(csv.string() + ": a profile needs at least two heights");
  const auto hi = std::max_element(rows.begin(), rows.end(),
                                   [&](auto& a, auto& b) { return a[height_col] < b[height_col]; });
  const auto lo = std::min_element(rows.begin(), rows.end(),
                                   [&](auto& a, auto& b) { return a[height_col] < b[height_col]; });
  if ((*hi)[height_col] == (*lo)[height_col])
    throw InputError(csv.string() + ": all rows have the same height");
  m.height_high_m = (*hi)[height_col] * height_scale;
  m.height_low_m = (*lo)[height_col] * height_scale;
  for (std::size_t k = 0; k < energy_cols.size(); ++k) {
    const double e = ((*lo)[energy_cols[k]] - (*hi)[energy_cols[k]]) * energy_scale[k];
    if (e < 0)
      throw InputError(fmt::format(
          "{}: column {}: the cumulative energy falls from {:g} at the highest row to {:g} at the "
          "lowest; it is the work done from the top down, so it grows as the blade descends "
          "(check the column's sign and that the heights are the blade's)",
          csv.string(), head[energy_cols[k]], (*hi)[energy_cols[k]], (*lo)[energy_cols[k]]));
    m.replicates_J.push_back(e);
  }
  return m;
}

Calibration calibrate(std::vector<CalibrationPoint> points, double measured_J,
                      double measured_se_J) {
  const auto n = points.size();
  std::set<double> distinct;
  for (const auto& p : points) distinct.insert(p.parameter);
  if (n < 3 || distinct.size() < 2)
    throw std::invalid_argument(fmt::format(
        "{} runs with {} distinct values of the parameter: the fit needs at least 3 runs and 2 "
        "values (3 or more values give the spread that sets the uncertainty)",
        n, distinct.size()));
  double mx = 0, my = 0;
  for (const auto& p : points) {
    mx += p.parameter;
    my += p.energy_J;
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (const auto& p : points) {
    sxx += (p.parameter - mx) * (p.parameter - mx);
    sxy += (p.parameter - mx) * (p.energy_J - my);
  }
  Calibration c;
  c.points = points;
  c.slope_J = sxy / sxx;
  c.intercept_J = my - c.slope_J * mx;
  double sse = 0;
  for (const auto& p : points) {
    const double r = p.energy_J - (c.intercept_J + c.slope_J * p.parameter);
    sse += r * r;
  }
  c.residual_sd_J = std::sqrt(sse / static_cast<double>(n - 2));
  const double se_slope = c.residual_sd_J / std::sqrt(sxx);
  if (!(std::fabs(c.slope_J) > 2 * se_slope))
    throw std::invalid_argument(fmt::format(
        "the simulated energy does not depend measurably on the parameter in these runs (slope "
        "{:.4g} J per unit, standard error {:.4g}): widen the studied range or run longer",
        c.slope_J, se_slope));
  c.measured_J = measured_J;
  c.measured_se_J = measured_se_J;
  c.parameter = (measured_J - c.intercept_J) / c.slope_J;
  const double line_var =
      c.residual_sd_J * c.residual_sd_J *
      (1.0 / static_cast<double>(n) + (c.parameter - mx) * (c.parameter - mx) / sxx);
  c.sigma_study = std::sqrt(line_var) / std::fabs(c.slope_J);
  c.sigma_measurement = measured_se_J / std::fabs(c.slope_J);
  c.sigma = std::hypot(c.sigma_study, c.sigma_measurement);
  c.extrapolated = c.parameter < *distinct.begin() || c.parameter > *distinct.rbegin();
  // the mean energy at each studied value, in the parameter's order; the pair bracketing the
  // measurement, if exactly one does
  std::vector<std::pair<double, double>> means;
  for (const double v : distinct) {
    double sum = 0;
    int count = 0;
    for (const auto& p : points)
      if (p.parameter == v) {
        sum += p.energy_J;
        ++count;
      }
    means.emplace_back(v, sum / count);
  }
  // (a measurement equal to a run's energy is bracketed by both pairs around that run, with the
  // same answer: that counts once)
  bool ambiguous = false;
  for (std::size_t i = 0; i + 1 < means.size(); ++i) {
    const auto [v0, w0] = means[i];
    const auto [v1, w1] = means[i + 1];
    if (w0 == w1 || measured_J < std::min(w0, w1) || measured_J > std::max(w0, w1)) continue;
    const double answer = v0 + (measured_J - w0) * (v1 - v0) / (w1 - w0);
    const double span = *distinct.rbegin() - *distinct.begin();
    if (c.bracketed && std::fabs(*c.bracketed - answer) > 1e-9 * span) ambiguous = true;
    if (c.bracketed) continue;
    c.bracketed = answer;
    c.bracket_low = v0;
    c.bracket_high = v1;
  }
  if (ambiguous) c.bracketed.reset();
  return c;
}

std::vector<std::filesystem::path> ft4Runs(const std::vector<std::filesystem::path>& folders) {
  std::vector<std::filesystem::path> runs;
  for (const auto& f : folders) {
    if (std::filesystem::exists(f / "scenario.resolved.yaml")) {
      runs.push_back(f);
      continue;
    }
    if (!std::filesystem::is_directory(f)) throw InputError(f.string() + ": not a folder");
    std::vector<std::filesystem::path> found;
    for (const auto& e : std::filesystem::directory_iterator(f)) {
      const auto name = e.path().filename().string();
      // a study keeps a replaced variant as variant-NN.previous-K: not part of the study
      if (!e.is_directory() || name.find(".previous") != std::string::npos) continue;
      if (!std::filesystem::exists(e.path() / "summary.json")) continue;
      const auto summary = readJsonFile(e.path() / "summary.json");
      if (summary.value("status", "") == "completed") found.push_back(e.path());
    }
    if (found.empty())
      throw InputError(f.string() +
                       ": neither a run folder (scenario.resolved.yaml) nor a study "
                       "folder with completed runs in it");
    std::sort(found.begin(), found.end());
    runs.insert(runs.end(), found.begin(), found.end());
  }
  return runs;
}

std::vector<CalibrationPoint> calibrationPoints(const std::vector<std::filesystem::path>& runs,
                                                const std::string& parameter,
                                                const MeasuredEnergy& measured) {
  std::vector<CalibrationPoint> points;
  for (const auto& run : runs) {
    const auto par = readFt4RunParameters(run, parameter);
    const auto profile = runFlowEnergy(run);
    double w = profile.total_J();
    if (measured.height_low_m) {
      try {
        w = profile.between(*measured.height_low_m, *measured.height_high_m);
      } catch (const std::invalid_argument& e) {
        throw InputError(run.string() + ": " + e.what() +
                         " (the measured profile's range); compare over a range both "
                         "cover");
      }
    }
    points.push_back({run, par.parameter, w});
  }
  return points;
}

bool Calibration::changesSign() const {
  if (points.empty()) return false;
  const auto [lo, hi] = std::minmax_element(
      points.begin(), points.end(), [](const CalibrationPoint& a, const CalibrationPoint& b) {
        return a.parameter < b.parameter;
      });
  return (lo->parameter >= 0 && parameter < 0) || (hi->parameter <= 0 && parameter > 0);
}

Json calibrationJson(const Calibration& c, const std::string& parameter) {
  Json points = Json::array();
  for (const auto& p : c.points)
    points.push_back(
        {{"run", p.run.string()}, {"parameter", p.parameter}, {"energy_J", p.energy_J}});
  return {{"parameter_name", parameter},
          {"parameter", c.parameter},
          {"sigma", c.sigma},
          {"sigma_study", c.sigma_study},
          {"sigma_measurement", c.sigma_measurement},
          {"extrapolated", c.extrapolated},
          {"bracketed", c.bracketed ? Json(*c.bracketed) : Json(nullptr)},
          {"bends", c.bends()},
          {"changes_sign", c.changesSign()},
          {"intercept_J", c.intercept_J},
          {"slope_J", c.slope_J},
          {"residual_sd_J", c.residual_sd_J},
          {"measured_J", c.measured_J},
          {"measured_se_J", c.measured_se_J},
          {"points", points}};
}

std::string calibrationText(const Calibration& c, const std::string& parameter) {
  std::string s = fmt::format("{:<12} {:>14}  run\n", parameter, "energy [mJ]");
  for (const auto& p : c.points)
    s += fmt::format("{:<12.6g} {:>14.6g}  {}\n", p.parameter, p.energy_J * 1e3, p.run.string());
  s += fmt::format("fit: W = {:.6g} mJ + {:.6g} mJ x {} (residual spread {:.3g} mJ over {} runs)\n",
                   c.intercept_J * 1e3, c.slope_J * 1e3, parameter, c.residual_sd_J * 1e3,
                   c.points.size());
  s += fmt::format("measured: {:.6g} mJ (standard error {:.3g} mJ)\n", c.measured_J * 1e3,
                   c.measured_se_J * 1e3);
  // four decimals for the parameter's usual range; significant digits for a value a measurement
  // far outside the runs extrapolates to (1e308 mJ printed 300 digits)
  auto value = [](double x) {
    return std::fabs(x) < 1e4 ? fmt::format("{:.4f}", x) : fmt::format("{:.4g}", x);
  };
  s += fmt::format(
      "{} = {} +- {} (study spread {}, measurement {}){}\n", parameter, value(c.parameter),
      value(c.sigma), value(c.sigma_study), value(c.sigma_measurement),
      c.extrapolated ? "; outside the studied values: extrapolated, extend the study" : "");
  if (c.changesSign())
    s += fmt::format(
        "warning: {} = {} has the other sign than every studied value: no {} of the studied "
        "sign reproduces {:.6g} mJ (the runs' energies are all on one side of it); check the "
        "measurement's units and the scene's vessel, mass and aeration before the parameter\n",
        parameter, value(c.parameter), parameter, c.measured_J * 1e3);
  if (c.bracketed) {
    s += fmt::format("between the runs at {} = {:g} and {:g}, whose energies bracket it: {}\n",
                     parameter, c.bracket_low, c.bracket_high, value(*c.bracketed));
    if (c.bends())
      s += fmt::format(
          "warning: the line and the bracketing runs differ by more than the uncertainty: the "
          "energy is not linear in {} over the studied values (it bends); study more values "
          "around {} and calibrate on those\n",
          parameter, value(*c.bracketed));
  }
  return s;
}

}  // namespace cosim::analysis
