// Independent reference for a packed bed's pressure drop: the drag law of the scene evaluated
// on the voidage of each CFD cell (as cosimFoam wrote it to the run's last time folder) and
// integrated over the column. Written here from the published formulas, not from models/.
//
// Gas momentum of a resting bed (model A, parcels at rest, steady, no inertia):
//   -dp/dz = 18 mu (1 - eps) f(eps, Re) u / (eps^2 d^2) + rho g
// with u the local superficial velocity, d the real particle diameter, Re = rho d u / mu, and
// f the dimensionless drag per real particle that multiplies 3 pi mu d (U - v):
//   Beetstra et al. (2007):  f = eps F(eps, Re)
//   Ergun (1952) as in Gidaspow (eps < 0.8):  f = (25/3)(1 - eps)/eps + (1.75/18) Re/eps,
//     which gives -dp/dz = 150 mu (1-eps)^2 u/(eps^3 d^2) + 1.75 rho (1-eps) u^2/(eps^3 d)
//   Wen & Yu (1966) (Gidaspow, eps >= 0.8): f = (1 + 0.15 Re^0.687) eps^-2.65
// The cells of one horizontal layer carry the flow in parallel at one pressure gradient G:
// mean over the layer of u_i(G) = u0, with u_i solving G = R(eps_i, u_i) u_i.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cosim::verification {

inline double beetstraF(double eps, double Re) {
  const double phi = 1.0 - eps;
  const double low = 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * std::sqrt(phi));
  if (Re <= 0.0) return low;
  const double num = 1.0 / eps + 3.0 * eps * phi + 8.4 * std::pow(Re, -0.343);
  const double den = 1.0 + std::pow(10.0, 3.0 * phi) * std::pow(Re, -(1.0 + 4.0 * phi) / 2.0);
  return low + 0.413 * Re / (24.0 * eps * eps) * num / den;
}

inline double beetstraDimensionless(double eps, double Re) { return eps * beetstraF(eps, Re); }

inline double ergunWenYuDimensionless(double eps, double Re) {
  if (eps < 0.8) return (25.0 / 3.0) * (1.0 - eps) / eps + (1.75 / 18.0) * Re / eps;
  return (1.0 + 0.15 * std::pow(Re, 0.687)) * std::pow(eps, -2.65);
}

// Internal field of an OpenFOAM ascii volScalarField file (uniform or nonuniform List).
inline std::vector<double> readFoamScalarField(const std::filesystem::path& file, std::size_t n) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const auto at = text.find("internalField");
  if (at == std::string::npos) throw std::runtime_error(file.string() + ": no internalField");
  std::istringstream s(text.substr(at + 13));
  std::string kind;
  s >> kind;
  std::vector<double> v;
  if (kind == "uniform") {
    double x;
    s >> x;
    v.assign(n, x);
    return v;
  }
  std::string type;
  std::size_t count = 0;
  char paren;
  s >> type >> count >> paren;
  v.resize(count);
  for (auto& x : v) s >> x;
  if (!s || count != n)
    throw std::runtime_error(file.string() + ": expected " + std::to_string(n) + " cells");
  return v;
}

// The newest numeric time folder of an OpenFOAM case.
inline std::filesystem::path latestTime(const std::filesystem::path& caseDir) {
  std::filesystem::path best;
  double tbest = -1;
  for (const auto& e : std::filesystem::directory_iterator(caseDir)) {
    if (!e.is_directory()) continue;
    try {
      std::size_t used = 0;
      const std::string name = e.path().filename().string();
      const double t = std::stod(name, &used);
      if (used == name.size() && t > tbest) tbest = t, best = e.path();
    } catch (...) {
    }
  }
  return best;
}

struct Gas {
  double rho, mu;
};

// Pressure drop of the particles alone [Pa] over a column of nz layers of nxy cells of height dz
// (cell index = i + nxy * k), superficial velocity u0, real particle diameter d.
inline double bedPressureDrop(const std::vector<double>& eps, std::size_t nxy, double dz, double u0,
                              double d, Gas g, const std::function<double(double, double)>& f) {
  const std::size_t nz = eps.size() / nxy;
  auto velocityAt = [&](double e, double G) -> double {  // u with R(e, u) u = G (fixed point on Re)
    if (e >= 1.0) return INFINITY;
    double u = u0;
    for (int it = 0; it < 200; ++it) {
      const double R = 18.0 * g.mu * (1.0 - e) * f(e, g.rho * d * u / g.mu) / (e * e * d * d);
      const double next = G / R;
      if (std::fabs(next - u) < 1e-14 * std::max(u, 1e-30)) return next;
      u = next;
    }
    return u;
  };
  double total = 0;
  for (std::size_t k = 0; k < nz; ++k) {
    bool solids = false;
    for (std::size_t i = 0; i < nxy; ++i) solids |= eps[i + nxy * k] < 1.0;
    if (!solids) continue;
    auto mean = [&](double G) -> double {
      double s = 0;
      for (std::size_t i = 0; i < nxy; ++i) {
        const double u = velocityAt(eps[i + nxy * k], G);
        if (!std::isfinite(u)) return INFINITY;
        s += u;
      }
      return s / double(nxy);
    };
    // bisection on G for mean(u) = u0 (mean is increasing in G)
    double lo = 0, hi = 1;
    while (mean(hi) < u0) hi *= 2;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (mean(mid) < u0 ? lo : hi) = mid;
    }
    total += 0.5 * (lo + hi) * dz;
  }
  return total;
}

}  // namespace cosim::verification
