#!/usr/bin/env python3
"""Independent reference numbers of the verification scenes (tests/verification).

Every literal in tests/verification/*.cpp that is a physics reference is printed here, from the
textbook formulas (not from cosim code). Run: python3 tests/verification/reference.py
"""
import math


def brentq(f, a, b, **_):
    """Bisection to machine precision (no scipy needed)."""
    fa = f(a)
    for _ in range(200):
        m = 0.5 * (a + b)
        fm = f(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def rk4(rhs, y0, t_end, n=200000):
    """Classical Runge-Kutta, n steps; returns the final state."""
    h = t_end / n
    y = list(y0)
    t = 0.0
    for _ in range(n):
        k1 = rhs(t, y)
        k2 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(y, k1)])
        k3 = rhs(t + h / 2, [a + h / 2 * b for a, b in zip(y, k2)])
        k4 = rhs(t + h, [a + h * b for a, b in zip(y, k3)])
        y = [a + h / 6 * (p + 2 * q + 2 * r + s) for a, p, q, r, s in zip(y, k1, k2, k3, k4)]
        t += h
    return y

g = 9.81
R = 8.314462618
# cosimFoam's gas: N2 perfect gas at 300 K, 1e5 Pa, mu = 1.8e-5 Pa s (adapters/openfoam GasSettings)
M_N2, T, P = 0.0280134, 300.0, 1.0e5
rho_g = P * M_N2 / (R * T)
mu_g = 1.8e-5


def sn_f(Re):
    """Schiller-Naumann drag factor f = Cd Re / 24 (Re < 1000)."""
    return 1.0 + 0.15 * Re**0.687


def terminal_sn(d, rho_p, rho_f=rho_g, mu=mu_g):
    """Slip w with (rho_p - rho_f) g pi d^3/6 = 3 pi mu d w f(Re), Re = rho_f w d / mu."""
    def bal(w):
        Re = rho_f * w * d / mu
        return (rho_p - rho_f) * g * d**2 / 18.0 - mu * w * sn_f(Re)
    w = brentq(bal, 1e-12, 100.0, xtol=1e-15, rtol=1e-15)
    return w, rho_f * w * d / mu


def slip_history_sn(d, rho_p, t_end, rho_f=rho_g, mu=mu_g):
    """Particle launched with the gas (zero slip): m dw/dt = (m - m_f) g - 3 pi mu d w f(Re);
    returns (slip, distance the particle lags behind the gas) at t_end."""
    m = rho_p * math.pi * d**3 / 6
    mf = rho_f * math.pi * d**3 / 6
    def rhs(t, y):
        w = y[0]
        Re = rho_f * abs(w) * d / mu
        return [((m - mf) * g - 3 * math.pi * mu * d * w * sn_f(Re)) / m, w]
    return rk4(rhs, [0.0, 0.0], t_end, 20000)


def main():
    print(f"gas: rho = {rho_g:.6f} kg/m3, mu = {mu_g} Pa s")
    print("== 1. terminal velocity (slip) of one sphere in N2 ==")
    # Stokes case
    d, rho_p = 20e-6, 1000.0
    vt = (rho_p - rho_g) * g * d**2 / (18 * mu_g)
    tau = rho_p * d**2 / (18 * mu_g)
    t_end = 0.01  # stokes.yaml end_time
    print(f"stokes: d={d} rho_p={rho_p}: v_t = {vt:.9e} m/s, Re = {rho_g*vt*d/mu_g:.4f}, tau = {tau:.4e} s, "
          f"slip at t_end={t_end}: {vt * (1 - math.exp(-t_end / tau)):.9e}")
    # stiff drag (stiff_drag_test.cpp): stokes.yaml with d = 1.8 um
    d = 1.8e-6
    print(f"stiff drag: d={d}: v_t = {(rho_p - rho_g) * g * d**2 / (18 * mu_g):.9e} m/s, "
          f"tau = {rho_p * d**2 / (18 * mu_g):.4e} s")
    # t_end: the end_time of scenario.yaml (0.5 s) and re100.yaml (1.2 s)
    for name, d, rho_p, t_end in (("re10", 180e-6, 1500.0, 0.5), ("re100", 600e-6, 1200.0, 1.2)):
        w, Re = terminal_sn(d, rho_p)
        ws, z = slip_history_sn(d, rho_p, t_end)
        taul = rho_p * d**2 / (18 * mu_g * (1 + 0.15 * 1.687 * Re**0.687))
        print(f"{name}: d={d} rho_p={rho_p}: w_t = {w:.9e} m/s, Re_t = {Re:.4f}, tau_lin = {taul:.4f} s, "
              f"slip at t_end={t_end}: {ws:.9e} ({ws/w - 1:+.2e}), "
              f"distance travelled relative to the gas {z:.4f} m")

    print("== 3. coating against Eq. 7 (scenarios/verify-coating) ==")
    d, eps, slip, rho, mu, Sc, Y, t = 300e-6, 0.6, 0.5, 1.12, 1.8e-5, 1.0, 0.011, 0.05
    Re = rho * eps * d * slip / mu
    Sh = (7 - 10 * eps + 5 * eps**2) * (1 + 0.17 * Re**0.2 * Sc**(1 / 3)) + \
        (1.33 - 2.31 * eps + 1.16 * eps**2) * Re**0.7 * Sc**(1 / 3)
    Km = Sh * (mu / (rho * Sc)) / d
    rate = Km * Y * rho * math.pi * d**2
    print(f"Re = {Re:.6f}, Sh = {Sh:.10f}, K_m = {Km:.10f} m/s, dm/dt = {rate:.10e} kg/s, "
          f"m({t} s) = {rate * t:.10e} kg per grain in the zone ({rate * t:.16e})")


if __name__ == "__main__":
    main()
