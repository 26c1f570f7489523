#!/usr/bin/python3
"""Reference numbers of the build-up kernel of models.drag.undisturbed_velocity:
self_disturbance_transient (docs/models.md, "Build-up in time").

The gas of a cubic cell of side Delta (7-point Laplacian, implicit in time or not) answers a
force F switched on at t = 0 in that cell with u(t) = -(2/3) F / (mu Delta) C(tau),
tau = nu t / Delta^2, where

    C(tau) = int_0^tau [exp(-2s) I0(2s)]^3 ds        (on-site heat kernel of the lattice)
    C(inf) = 0.2527310098586630 = Watson's integral / 6

S(tau) = C(tau) / C(inf) is the build-up. This script
  1. integrates C(tau) with scipy (quad of the scaled Bessel product) and prints S at a few tau
     (tests/models/undisturbed_velocity_test.cpp asserts the C++ kernel against them);
  2. fits 1 - S(tau) = sum_i w_i exp(-lambda_i tau) with fixed lambda_i (log-spaced, in the
     lattice's spectrum [0, 12]) and w_i >= 0 (non-negative least squares, with sum w_i = 1 and
     sum w_i lambda_i = 1 / C(inf), the slope at 0, as heavily weighted rows), and prints the
     C++ table (models/src/drag/wake_buildup.cpp);
  3. prints the response after m implicit-Euler steps of tau_s each (the gas solver's time
     scheme), S_IE(m) = sum over j = 1..m of tau_s int dRho(lambda) (1 + tau_s lambda)^-j / C(inf)
     with int dRho (1 + a lambda)^-j = 1 / Gamma(j) int_0^inf s^(j-1) e^-s f(a s)^3 ds, computed
     directly (not from the fit), against which the modes' implicit update is tested;
  4. prints the response of a neighbouring cell, C1(tau) = int_0^tau exp(-6s) I1(2s) I0(2s)^2 ds
     (the modes carry it over with the factor 1 - lambda_i / 6, exact per lattice mode).

Run: /usr/bin/python3 scenarios/verify-wake/kernel.py   (python3-numpy, python3-scipy)
"""
import math

import numpy as np
from scipy import integrate, optimize, special

WATSON_OVER_6 = 0.2527310098586630


def f3(s):
    """[exp(-2s) I0(2s)]^3: the on-site return probability of the lattice walk."""
    return special.ive(0, 2.0 * s) ** 3


def C(tau):
    """int_0^tau f3, in pieces on a log grid (the integrand falls as s^-3/2)."""
    if tau <= 0:
        return 0.0
    edges = [0.0] + [x for x in np.logspace(-3, 7, 101) if x < tau] + [tau]
    return sum(integrate.quad(f3, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
               for a, b in zip(edges[:-1], edges[1:]))


def C_inf():
    # int_0^T f3 + the tail from the asymptotic series of ive(0, x)^3, x = 2s:
    # ive(0, x) = (2 pi x)^-1/2 (1 + 1/(8x) + 9/(128 x^2) + ...), so f3 ~ (4 pi s)^-3/2 (1 + 3/(16 s) + ...)
    T = 1e7
    tail = 2.0 * (4 * math.pi) ** -1.5 * T ** -0.5 * (1 + 3 / (16 * 3 * T))
    return C(T) + tail


def C1(tau):
    """Neighbouring cell: int_0^tau ive(1, 2s) ive(0, 2s)^2 ds."""
    g = lambda s: special.ive(1, 2 * s) * special.ive(0, 2 * s) ** 2
    edges = [0.0] + [x for x in np.logspace(-3, 7, 101) if x < tau] + [tau]
    return sum(integrate.quad(g, a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
               for a, b in zip(edges[:-1], edges[1:]))


def S_implicit_euler(m, tau_s, cinf):
    """Build-up after m implicit-Euler steps of tau_s under a constant force (exact lattice)."""
    total = 0.0
    for j in range(1, m + 1):
        g = lambda s: s ** (j - 1) * math.exp(-s - math.lgamma(j)) * f3(tau_s * s)
        hi = j + 60 * math.sqrt(j) + 60
        edges = [0.0] + [x for x in np.logspace(-4, math.log10(hi), 40)]
        total += tau_s * sum(integrate.quad(g, a, b, epsabs=0, epsrel=1e-12, limit=200)[0]
                             for a, b in zip(edges[:-1], edges[1:]))
    return total / cinf


def fit(cinf, lambdas):
    taus = np.concatenate([[0.0], np.logspace(-4, 7, 221)])
    target = np.array([1.0 - C(t) / cinf for t in taus])
    # relative weighting where 1 - S is small (the tail matters to the 0.1 %)
    rows = np.exp(-np.outer(taus, lambdas)) / np.maximum(target, 1e-4)[:, None]
    rhs = target / np.maximum(target, 1e-4)
    big = 1e4
    rows = np.vstack([rows, big * np.ones(len(lambdas)), big * cinf * lambdas])
    rhs = np.concatenate([rhs, [big, big]])
    w, _ = optimize.nnls(rows, rhs, maxiter=100000)
    err = max(abs(sum(w * np.exp(-lambdas * t)) - (1.0 - C(t) / cinf)) for t in taus)
    return w, err


def main():
    cinf = C_inf()
    print(f"C(inf) = {cinf:.13f}   Watson/6 = {WATSON_OVER_6:.13f}")
    print("\nS(tau) = C(tau)/C(inf), and the tail 1 - S against 2 (4 pi)^-3/2 tau^-1/2 / C(inf):")
    for tau in [0.01, 0.1, 0.5, 1, 2, 5, 10, 32, 89, 100, 200, 1000]:
        s = C(tau) / cinf
        print(f"  tau {tau:8g}: S = {s:.10f}   1 - S = {1 - s:.6e}   "
              f"asymptote {2 * (4 * math.pi) ** -1.5 / math.sqrt(tau) / cinf:.6e}")

    lambdas = 12.0 * 10.0 ** (-np.arange(0, 24) / 3.0)  # 12 .. 12e-23/3: 3 per decade
    lambdas = lambdas[lambdas > 1e-7]
    w, err = fit(cinf, lambdas)
    keep = w > 0
    lambdas, w = lambdas[keep], w[keep]
    print(f"\nfit: {len(w)} modes, max |error| of 1 - S over tau in [0, 1e7]: {err:.2e}")
    print(f"  sum w = {w.sum():.15f}, sum w lambda * C(inf) = {(w * lambdas).sum() * cinf:.15f}")
    for tau in [0.01, 0.1, 1, 2, 10, 32, 89, 200, 1000, 1e4]:
        s_fit = 1 - sum(w * np.exp(-lambdas * tau))
        print(f"  tau {tau:8g}: fit S = {s_fit:.8f}, exact {C(tau) / cinf:.8f}, "
              f"diff {s_fit - C(tau) / cinf:+.2e}")
    print("\nC++ table (lambda_i, w_i):")
    for l, x in zip(lambdas, w):
        print(f"    {{{l:.17g}, {x:.17g}}},")

    print("\nimplicit Euler, m steps of tau_s (exact lattice | modes 1 - sum w (1 + lambda tau_s)^-m):")
    for tau_s in [0.32, 0.89, 2.0]:
        for m in [1, 2, 5, 20]:
            exact = S_implicit_euler(m, tau_s, cinf)
            modes = 1 - sum(w * (1 + lambdas * tau_s) ** (-m))
            print(f"  tau_s {tau_s}: m {m:3d}: exact {exact:.8f}  modes {modes:.8f}  "
                  f"diff {modes - exact:+.2e}   (continuous S(m tau_s) {C(m * tau_s) / cinf:.8f})")

    print("\nneighbouring cell: C1(tau)/C(inf) exact | modes sum w (1 - lambda/6)(1 - e^-lambda tau):")
    print(f"  steady: exact {1 - 1 / (6 * cinf):.8f} (= 1 - 1/(6 C(inf))), "
          f"modes {sum(w * (1 - lambdas / 6)):.8f}")
    for tau in [0.1, 1, 10, 100]:
        exact = C1(tau) / cinf
        modes = sum(w * (1 - lambdas / 6) * (1 - np.exp(-lambdas * tau)))
        print(f"  tau {tau:6g}: exact {exact:.8f}  modes {modes:.8f}  diff {modes - exact:+.2e}")


if __name__ == "__main__":
    main()
