#!/usr/bin/python3
"""Steady state of a held sphere of verify-wake, from two runs' written gas fields alone
(independent of cosim's code; docs/verification.md, section 4, "the held sphere at its steady
state"): one with `none` (the gas gets K (U_P - 0)), one with `self_disturbance` (the gas gets
the steady estimate's K_eff (U_P - 0), K_eff = K / (1 - a), a = K G).

For each of the last written times it prints
  U_P / u_up            the gas velocity of the sphere's cell
  F / (K u_up) - 1      the drag against Stokes drag on the undisturbed gas (the error a free
                        sphere's terminal velocity carries, with the opposite sign, at equilibrium)
and, from the two runs together, the split of the operator's answer into
  U_P = (1 + beta) u_up - gamma G F
(beta: the cell's own voidage raising its reconstructed velocity without any force; gamma: the
response per unit force against the lattice's G = c_v / (eps_f mu Delta) with its advective
part, as models/include/cosim/models/drag/undisturbed_velocity.h writes it).

Run the scene held (no gravity, a density no drag moves; `g`, `rho_p` and `write_steps` are
parameters of scenario.yaml), at the time step and solver settings to calibrate, for example
  cosim run scenarios/verify-wake -o NONE --set models.drag.undisturbed_velocity=none \\
      --set end_time=1.0 --set g=0 --set rho_p=1e15 --set write_steps=250
  cosim run scenarios/verify-wake -o STEADY --set models.drag.undisturbed_velocity=self_disturbance \\
      (same --set)
  scenarios/verify-wake/held_forms.py NONE STEADY --n-d 2
It ends with gamma and beta as the two keys of models.drag that calibrate the estimate for this
mesh, particle and solver settings (docs/models.md, "Calibrating for the gas solver").

Needs numpy (Debian's python3-numpy) for disturbance.py's reader.
"""
import argparse
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from disturbance import C_V, internal_field  # noqa: E402


def cell_velocities(run, cell, last):
    fluid = os.path.join(run, "fluid")
    times = sorted((t for t in os.listdir(fluid) if re.fullmatch(r"[0-9.e+-]+", t) and float(t) > 0),
                   key=float)
    return [(float(t), internal_field(os.path.join(fluid, t, "U"))[cell][2]) for t in times[-last:]]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("none_run")
    ap.add_argument("steady_run")
    ap.add_argument("--n-d", type=float, default=2, help="cell size in diameters")
    ap.add_argument("--d", type=float, default=20e-6)
    ap.add_argument("--n-cells", type=int, default=23)
    ap.add_argument("--u-up", type=float, default=1.211111111e-2)
    ap.add_argument("--mu", type=float, default=1.8e-5)
    ap.add_argument("--rho", type=float, default=1.2)
    ap.add_argument("--last", type=int, default=3, help="how many of the last written times")
    a = ap.parse_args()

    d, Delta, mu, u = a.d, a.n_d * a.d, a.mu, a.u_up
    m = a.n_cells // 2
    cell = m + a.n_cells * m + a.n_cells * a.n_cells * m
    eps = 1.0 - math.pi / 6.0 * d ** 3 / Delta ** 3
    eps_f = 0.5 * (1.0 + eps)
    K = 3.0 * math.pi * mu * d

    def G(U):
        return 1.0 / (eps_f * mu * Delta / C_V + eps * a.rho * abs(U) * Delta ** 2)

    rows = []
    print("| t [s] | U_P/u_up none | F/(K u_up) - 1 none | U_P/u_up steady | F/(K u_up) - 1 steady "
          "| gamma | beta | beta/(1 - eps) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for (t, Un), (_, Us) in zip(cell_velocities(a.none_run, cell, a.last),
                                cell_velocities(a.steady_run, cell, a.last)):
        Fn = K * Un
        Fs = K * Us / (1.0 - min(K * G(Us), 0.9))
        gfn, gfs = G(Un) * Fn / u, G(Us) * Fs / u
        gamma = (Un - Us) / u / (gfs - gfn)
        beta = Un / u + gamma * gfn - 1.0
        print("| %.2f | %.5f | %+.2f %% | %.5f | %+.2f %% | %.4f | %.4f | %.2f |"
              % (t, Un / u, 100 * (Fn / (K * u) - 1), Us / u, 100 * (Fs / (K * u) - 1), gamma, beta,
                 beta / (1.0 - eps)))
        rows.append((gamma, beta))
    if rows:
        gamma, beta = rows[-1]
        print("\nthe calibration of this mesh, particle and solver settings (docs/models.md,"
              " \"Calibrating for the gas solver\"), from the last written time:")
        print("  models.drag.self_disturbance_gain: %.4f" % gamma)
        print("  models.drag.self_disturbance_offset: %.4f" % beta)
        if len(rows) > 1:
            print("  (change over the last %d written times: gain %.1e, offset %.1e: the held runs"
                  " must have reached their steady state)"
                  % (len(rows), abs(rows[-1][0] - rows[0][0]), abs(rows[-1][1] - rows[0][1])))


if __name__ == "__main__":
    main()
