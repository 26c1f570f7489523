#include "cosim/models/drag/radl_sundaresan.h"

#include <algorithm>
#include <cmath>

#include "cosim/models/drag/beetstra.h"

namespace cosim::models {

double radlSundaresanA(double phi) {
  if (phi < 0.016) return 21.51;
  if (phi < 0.10) return 1.96 + phi * (29.40 + phi * (164.91 - 1923.0 * phi));
  if (phi < 0.18) {
    const double x = phi - 0.10;
    return 4.63 + x * (4.68 + x * (-412.04 + 2254.0 * x));
  }
  if (phi < 0.25) {
    const double x = phi - 0.18;
    return 3.52 + x * (-17.99 + x * (128.80 - 603.0 * x));
  }
  if (phi < 0.40) {
    const double x = phi - 0.25;
    return 2.68 + x * (-8.20 + x * (2.18 + 112.33 * x));
  }
  return 1.79;
}

double radlSundaresanH(double phi) {
  auto cubic = [](double x, double c0, double c1, double c2, double c3) {
    return c0 + x * (c1 + x * (c2 + c3 * x));
  };
  if (phi < 0.03) return 7.97 * phi;
  if (phi < 0.08) return cubic(phi - 0.03, 0.239, 4.64, -4.41, 253.63);
  if (phi < 0.12) return cubic(phi - 0.08, 0.492, 6.10, 33.63, -789.6);
  if (phi < 0.18) return cubic(phi - 0.12, 0.739, 5.01, -61.1, 310.8);
  if (phi < 0.34) return cubic(phi - 0.18, 0.887, 1.03, -5.17, 5.99);
  if (phi < 0.48) return cubic(phi - 0.34, 0.943, -0.17, -2.29, -9.12);
  if (phi < 0.55) return cubic(phi - 0.48, 0.850, -1.35, -6.13, -132.6);
  // Last piece reaches 0 near phi = 0.60 (close packing); beyond it the fit is extrapolated and
  // would turn negative (a filtered drag above the microscopic one): bounded at 0.
  return std::max(0.0, cubic(phi - 0.55, 0.680, -2.34, -225.2, 0.0));
}

namespace {
// Single sphere (phi = 0) with Beetstra's F, as a function of x = ln Re:
//   F(1, Re) = 1 + c A B,  A = Re + 8.4 Re^0.657,  B = sqrt(Re) / (1 + sqrt(Re)),  c = 0.413/24
// returns ln F and dlnF/dx = Re F'(Re) / F (two exp and one log per call).
struct SingleSphere {
  double lnF, dlnF;
};
SingleSphere singleSphere(double x) {
  constexpr double c = 0.413 / 24.0;
  const double Re = std::exp(x);
  const double s = std::exp(0.5 * x);    // sqrt(Re)
  const double q = std::exp(0.657 * x);  // Re^0.657
  const double A = Re + 8.4 * q;
  const double ReDA = Re + 8.4 * 0.657 * q;  // Re dA/dRe
  const double B = s / (s + 1.0);
  const double ReDB = 0.5 * s / ((s + 1.0) * (s + 1.0));  // Re dB/dRe
  const double F = 1.0 + c * A * B;
  return {std::log(F), c * (ReDA * B + A * ReDB) / F};
}
}  // namespace

double beetstraTerminalVelocity(double d, double rho_p, double rho, double mu, double g) {
  return beetstraTerminalVelocity(d, rho_p, rho, mu, g, 0.0);
}

double beetstraTerminalVelocity(double d, double rho_p, double rho, double mu, double g,
                                double guess) {
  // Force balance (rho_p - rho) g pi d^3/6 = 3 pi mu d u_t F(1, Re_t), times rho d / mu^2:
  //   Ar / 18 = Re_t F(1, Re_t), i.e. h(x) = x + ln F(1, e^x) - ln T = 0 with x = ln Re_t.
  //   h' = 1 + Re F'/F in [1, 2]: Newton, kept inside the bracket [ln T - ln F(1, T), ln T]
  //   (F >= 1 and increasing), bisection whenever Newton would leave it.
  const double T = rho * (rho_p - rho) * g * d * d * d / (18.0 * mu * mu);
  const double lnT = std::log(T);
  double hi = lnT;
  double lo = lnT - singleSphere(lnT).lnF;
  // Start from the guess (e.g. the neighbour parcel's Re_t) when it lies in the bracket.
  const double lng = guess > 0.0 ? std::log(guess) : lo;
  double x = (lng > lo && lng < hi) ? lng : lo;
  for (int it = 0; it < 200; ++it) {
    const SingleSphere ss = singleSphere(x);
    const double h = x + ss.lnF - lnT;
    if (h > 0.0)
      hi = std::min(hi, x);
    else
      lo = std::max(lo, x);
    double next = x - h / (1.0 + ss.dlnF);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - x) < 1e-14 * std::max(1.0, std::abs(x)) || hi - lo < 1e-15;
    x = next;
    if (done) break;
  }
  return std::exp(x) * mu / (rho * d);
}

double radlSundaresanLength(double u_t, double g, double d) {
  const double Fr = u_t * u_t / (g * d);
  return (u_t * u_t / g) * std::pow(Fr, -2.0 / 3.0);
}

double radlSundaresanCorrection(double phi, double L_c, double Delta) {
  return 1.0 - radlSundaresanH(phi) / (radlSundaresanA(phi) * L_c / Delta + 1.0);
}

}  // namespace cosim::models
