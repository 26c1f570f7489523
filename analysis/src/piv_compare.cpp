// Simulated against measured PIV profiles (piv_compare.h).
#include "cosim/analysis/piv_compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "cosim/analysis/files.h"
#include "cosim/analysis/user_csv.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxSpeed = 343;  // m/s, sound in air at 20 C: above any particle velocity

double parse(const std::string& text, bool empty_is_nan, const std::string& where) {
  if (text.empty() && empty_is_nan) return kNaN;
  std::size_t used = 0;
  double v = kNaN;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError(where + ": " + quotedCell(text) + " is not a finite number");
  return v;
}

// err: |v_sim - v_measured|; noise: the mean absolute error of noise alone at the point (NaN:
// not known)
void addTo(MaeEntry& e, double err, double noise) {
  e.mae += err;  // the sums until finish()
  ++e.points;
  if (std::isfinite(noise)) {
    e.noise_mae += noise;
    ++e.noise_points;
  }
}

void finish(MaeEntry& e) {
  e.mae = e.points > 0 ? e.mae / static_cast<double>(e.points) : kNaN;
  e.noise_mae = e.noise_points > 0 ? e.noise_mae / static_cast<double>(e.noise_points) : kNaN;
}

// The interpolated velocity at a point and its standard error (NaN: not known). Between two
// points v = (1 - w) v_lo + w v_hi, whose standard error, the two bins' errors independent, is
// sqrt((1 - w)^2 se_lo^2 + w^2 se_hi^2).
struct Sample {
  double v = 0, se = kNaN;
};

// The simulated profile at one height: points with data, sorted by x.
struct Curve {
  std::vector<double> x, v, se;
  double spacing = 0;
  std::optional<Sample> at(double xq) const {
    auto only = [&](std::size_t i) { return std::optional(Sample{v[i], se[i]}); };
    if (x.size() == 1) return std::fabs(xq - x[0]) <= spacing ? only(0) : std::nullopt;
    if (xq < x.front()) return x.front() - xq <= spacing ? only(0) : std::nullopt;
    if (xq > x.back()) return xq - x.back() <= spacing ? only(x.size() - 1) : std::nullopt;
    const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), xq) - x.begin());
    if (hi >= x.size()) return only(x.size() - 1);
    const std::size_t lo = hi - 1;
    const double w = (xq - x[lo]) / (x[hi] - x[lo]);
    return Sample{v[lo] + w * (v[hi] - v[lo]),
                  std::sqrt((1 - w) * (1 - w) * se[lo] * se[lo] + w * w * se[hi] * se[hi])};
  }
};
}  // namespace

std::vector<ProfilePoint> readProfileCsv(const std::filesystem::path& path) {
  UserCsv in(path, "a profile CSV with the columns height_m, x_m, vz_m_s");
  std::map<std::string, std::size_t> col;
  const auto& head = in.header();
  for (std::size_t i = 0; i < head.size(); ++i) {
    if (!col.emplace(head[i], i).second)
      throw InputError(in.where() + ": column " + quotedCell(head[i]) + " named twice");
  }
  for (const char* need : {"height_m", "x_m", "vz_m_s"}) {
    if (!col.count(need))
      throw InputError(in.where() + ": the header has no column '" + need +
                       "' (a profile CSV starts with a header naming height_m, x_m and vz_m_s)");
  }
  std::vector<ProfilePoint> out;
  for (std::vector<std::string> cells; in.next(cells);) {
    const std::string where = in.where();
    auto cell = [&](const char* name) -> const std::string& { return cells[col.at(name)]; };
    ProfilePoint p;
    p.height = parse(cell("height_m"), false, where + " column height_m");
    p.x = parse(cell("x_m"), false, where + " column x_m");
    p.vz = parse(cell("vz_m_s"), true, where + " column vz_m_s");
    // no particle in a bed outruns sound in air: a larger number is in other units
    if (std::fabs(p.vz) > kMaxSpeed)
      throw InputError(fmt::format(
          "{} column vz_m_s: {} m/s is faster than sound in air; the column is in m/s (a PIV "
          "export in mm/s or pixels per frame must be converted first)",
          where, p.vz));
    if (col.count("vz_stderr_m_s")) {
      p.stderr_vz = parse(cell("vz_stderr_m_s"), true, where + " column vz_stderr_m_s");
      if (p.stderr_vz < 0)
        throw InputError(where + " column vz_stderr_m_s: a standard error is >= 0");
    }
    out.push_back(p);
  }
  return out;
}

PivComparison comparePiv(const std::vector<ProfilePoint>& simulated,
                         const std::vector<ProfilePoint>& measured, const PivCompareOptions& o) {
  // Simulated heights, each with its curve.
  std::vector<std::pair<double, Curve>> curves;
  std::vector<double> grid_x;
  for (const auto& p : simulated) {
    auto it = std::find_if(curves.begin(), curves.end(), [&](const auto& c) {
      return std::fabs(c.first - p.height) <= o.height_tolerance;
    });
    if (it == curves.end()) {
      curves.emplace_back(p.height, Curve{});
      it = curves.end() - 1;
    }
    if (std::isfinite(p.vz)) {
      it->second.x.push_back(p.x);
      it->second.v.push_back(p.vz);
      it->second.se.push_back(p.stderr_vz);
    }
  }
  std::string heights;
  for (auto& entry : curves) {
    const double h = entry.first;
    Curve& c = entry.second;
    heights += (heights.empty() ? "" : ", ") + fmt::format("{} m", h);
    std::vector<std::size_t> order(c.x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return c.x[a] < c.x[b]; });
    Curve s;
    for (auto i : order) {
      s.x.push_back(c.x[i]);
      s.v.push_back(c.v[i]);
      s.se.push_back(c.se[i]);
    }
    s.spacing = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < s.x.size(); ++i)
      s.spacing = std::min(s.spacing, s.x[i] - s.x[i - 1]);
    if (s.x.size() < 2) s.spacing = 0;
    c = std::move(s);
  }
  PivComparison r;
  for (const auto& m : measured) {
    if (!std::isfinite(m.vz)) continue;
    const auto it = std::find_if(curves.begin(), curves.end(), [&](const auto& c) {
      return std::fabs(c.first - m.height) <= o.height_tolerance;
    });
    if (it == curves.end())
      throw InputError(fmt::format(
          "the measured profile at {} m has no simulated profile (simulated heights: {}): run "
          "`cosim piv RUN --heights ...` with that height{}",
          m.height, heights.empty() ? "none" : heights,
          m.height > 2 ? " (heights are in metres above the bottom: given in mm?)" : ""));
    if (it->second.x.empty())
      throw InputError(fmt::format(
          "the simulated profile at {} m has no data (no parcel seen in that band)", it->first));
    auto pc = std::find_if(r.profiles.begin(), r.profiles.end(),
                           [&](const auto& p) { return p.height == it->first; });
    if (pc == r.profiles.end()) {
      r.profiles.push_back(ProfileComparison{it->first, {}, {}, {}, 0});
      pc = r.profiles.end() - 1;
    }
    const auto sim = it->second.at(m.x);
    if (!sim) {
      ++pc->without_simulation;
      continue;
    }
    const double err = std::fabs(sim->v - m.vz);
    // E|X| of X ~ N(0, se_sim^2 + se_measured^2): what noise alone gives where both agree
    const double measured_se = std::isfinite(m.stderr_vz) ? m.stderr_vz : 0.0;
    const double noise = std::sqrt(2.0 / std::numbers::pi) *
                         std::sqrt(sim->se * sim->se + measured_se * measured_se);
    const bool core =
        o.core_band ? (m.x >= o.core_band->first && m.x <= o.core_band->second) : m.vz > 0;
    addTo(pc->all, err, noise);
    addTo(core ? pc->core : pc->sides, err, noise);
    addTo(r.all, err, noise);
    addTo(core ? r.core : r.sides, err, noise);
  }
  if (r.all.points == 0) {
    std::size_t with_value = 0;
    for (const auto& m : measured) with_value += std::isfinite(m.vz) ? 1 : 0;
    throw InputError(
        with_value == 0
            ? std::string("the measured file has no point with a velocity (every vz_m_s is "
                          "empty): nothing to compare")
            : fmt::format("none of the {} measured points lies within the simulated profiles' "
                          "x range (one bin width beyond the outermost bin): are the measured x "
                          "in metres from the vessel's centre?",
                          with_value));
  }
  for (auto& p : r.profiles) {
    finish(p.all);
    finish(p.core);
    finish(p.sides);
  }
  finish(r.all);
  finish(r.core);
  finish(r.sides);
  return r;
}

}  // namespace cosim::analysis
