#include "observables.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  return parts;
}

[[noreturn]] void bad(const std::string& q, const std::string& why) {
  throw InputError("observable quantity '" + q + "': " + why +
                   " (forms: particles.<field>[.x|y|z].<mean|min|max|std|cv|sum>, "
                   "series.<column>.<mean|final|min|max>, totals.<name>)");
}

[[noreturn]] void undefined(const std::string& q, const std::string& why) {
  throw UndefinedQuantity("observable quantity '" + q + "' has no value: " + why);
}

// `none`: why there are no values, for the message
double stat(const std::vector<double>& v, const std::string& s, const std::string& q,
            const std::string& none) {
  if (v.empty()) undefined(q, none);
  double sum = 0, mn = v[0], mx = v[0];
  for (double x : v) {
    sum += x;
    mn = std::min(mn, x);
    mx = std::max(mx, x);
  }
  const double mean = sum / static_cast<double>(v.size());
  if (s == "mean") return mean;
  if (s == "sum") return sum;
  if (s == "min") return mn;
  if (s == "max") return mx;
  if (s == "final") return v.back();
  if (s == "std" || s == "cv") {
    double var = 0;
    for (double x : v) var += (x - mean) * (x - mean);
    var /= static_cast<double>(v.size());
    const double sd = std::sqrt(var);
    if (s == "std") return sd;
    if (mean == 0.0) undefined(q, "cv of values whose mean is 0");
    return sd / mean;
  }
  bad(q, "unknown statistic '" + s + "'");
}

}  // namespace

void checkQuantity(const std::string& q) {
  auto p = split(q);
  if (p.empty()) bad(q, "empty");
  if (p[0] == "particles") {
    if (p.size() < 3 || p.size() > 4)
      bad(q, "expected particles.<field>[.<component>].<statistic>");
    if (field::components(p[1]) == 0) bad(q, "unknown particle field '" + p[1] + "'");
    if (p.size() == 4 && p[2] != "x" && p[2] != "y" && p[2] != "z")
      bad(q, "component must be x, y or z");
    if (p.size() == 3 && field::components(p[1]) != 1)
      bad(q, "field '" + p[1] + "' is a vector: give a component x, y or z");
    static const std::vector<std::string> stats = {"mean", "min", "max", "std", "cv", "sum"};
    if (std::find(stats.begin(), stats.end(), p.back()) == stats.end())
      bad(q, "unknown statistic '" + p.back() + "'");
  } else if (p[0] == "series") {
    if (p.size() != 3) bad(q, "expected series.<column>.<statistic>");
    static const std::vector<std::string> stats = {"mean", "final", "min", "max"};
    if (std::find(stats.begin(), stats.end(), p[2]) == stats.end())
      bad(q, "unknown statistic '" + p[2] + "'");
  } else if (p[0] == "totals") {
    if (p.size() != 2) bad(q, "expected totals.<name>");
  } else {
    bad(q, "must start with particles., series. or totals.");
  }
}

double evaluateQuantity(const std::string& q, const link::ParticleData& state,
                        const std::vector<double>& time,
                        const std::map<std::string, std::vector<double>>& series,
                        const std::map<std::string, double>& totals, double after) {
  checkQuantity(q);
  auto p = split(q);
  if (p[0] == "particles") {
    if (!state.has(p[1])) bad(q, "the run's particle state has no field '" + p[1] + "'");
    const auto& v = state.get(p[1]);
    const unsigned c = field::components(p[1]);
    std::vector<double> vals;
    const std::size_t comp = p.size() == 4 ? static_cast<std::size_t>(p[2][0] - 'x') : 0;
    for (std::size_t i = 0; i < state.size(); ++i) vals.push_back(v[c * i + comp]);
    return stat(vals, p.back(), q, "no particle was left in the domain at the end of the run");
  }
  if (p[0] == "series") {
    auto it = series.find(p[1]);
    if (it == series.end()) bad(q, "the run's time series has no column '" + p[1] + "'");
    std::vector<double> vals;
    for (std::size_t i = 0; i < time.size() && i < it->second.size(); ++i) {
      // rows without a value (NaN: the pressure drop of the initial row) are skipped
      if (time[i] >= after && std::isfinite(it->second[i])) vals.push_back(it->second[i]);
    }
    std::ostringstream none;
    none << "no row of timeseries.csv at t >= " << after << " s has a value of " << p[1] << " ("
         << time.size() << " rows";
    if (!time.empty()) none << ", the last at t = " << time.back() << " s";
    none << ")";
    return stat(vals, p[2], q, none.str());
  }
  auto it = totals.find(p[1]);
  if (it == totals.end()) bad(q, "the run has no total '" + p[1] + "'");
  return it->second;
}

std::optional<double> relativeError(double value, std::optional<double> reference) {
  if (!reference) return std::nullopt;
  const double d = std::fabs(value - *reference);
  return *reference == 0.0 ? d : d / std::fabs(*reference);
}

}  // namespace cosim::orchestrator
