#!/usr/bin/python3
"""The disturbance of the sphere's own cell against the lattice's built-up response G H, from a
verify-wake run alone (independent of cosim's code; docs/verification.md, section 4):

  d(t) = u_up - U_z(sphere's cell)           from the OpenFOAM fields the run wrote
  F(t) = the force the gas got each interval  free sphere: m dv/dt + m g from the particle's
                                              velocity in particles.h5 (one snapshot per step);
                                              held sphere (--held): K U_z(new) with `none`
  H(t) = the 21 modes of models/src/drag/wake_buildup.cpp advanced with implicit Euler by F
  G    = c_v / (eps_f mu Delta), the viscous lattice response (the advective part, ~1e-3 here, left out)

and prints d / (G H) at every written time: 1 where the gas answers as the infinite lattice.

Run the scene with the fields written often and one snapshot per step, e.g. (free sphere):
  sed -i 's/^writeInterval .*/writeInterval   5;/' COPY/cfd/system/controlDict
  cosim run COPY -o RUN --set models.drag.undisturbed_velocity=self_disturbance_transient \\
      --set end_time=0.06 --set output.interval=2e-4
  scenarios/verify-wake/disturbance.py RUN
For a held sphere remove `fix gravi` from COPY/dem/in.sphere, add --set rho_p=1e15 and
--set models.drag.undisturbed_velocity=none, and pass --held.

Needs h5py and numpy (Debian's python3-h5py, python3-numpy).
"""
import argparse
import os
import re

import h5py
import numpy as np

# models/src/drag/wake_buildup.cpp (fitted by kernel.py): (lambda_i, w_i)
MODES = [
    (12, 0.05759174590746844), (5.5699066003353348, 0.47127798563910717),
    (2.5853216280382609, 0.17861890554853685), (1.2000000000000002, 0.10989035152688645),
    (0.55699066003353348, 0.056224920079213862), (0.25853216280382596, 0.042915637713834588),
    (0.12, 0.026111078935457419), (0.055699066003353323, 0.018479752980988588),
    (0.025853216280382611, 0.012563608148065014), (0.012, 0.0081214038328018111),
    (0.005569906600335333, 0.0061377570475202444), (0.0025853216280382614, 0.0034891533711843316),
    (0.0012000000000000001, 0.0030952878317478537), (0.00055699066003353384, 0.0013989453673044407),
    (0.00025853216280382588, 0.0016138586704714968), (0.00012000000000000002, 0.00054891874714744083),
    (5.5699066003353387e-05, 0.00071918125054618357), (2.5853216280382585e-05, 0.00045968266001392713),
    (5.5699066003353387e-06, 0.00047087613675032917), (2.5853216280382585e-06, 3.8249783970350883e-05),
    (2.5853216280382588e-07, 0.00023269861038862646),
]
C_V = 2.0 / 3.0 * 0.2527310


def internal_field(path):
    """The internalField of an ASCII OpenFOAM field file: a list of floats or of 3-tuples."""
    text = open(path).read()
    body = text[text.index("internalField"):]
    head = body.split("\n", 1)[0]
    if "nonuniform" not in head:
        inner = head.split("uniform", 1)[1].strip().rstrip(";").strip()
        if inner.startswith("("):
            return [tuple(float(x) for x in inner.strip("()").split())]
        return [float(inner)]
    n = int(re.search(r"\n(\d+)\n\(", body).group(1))
    start = body.index("(", body.index("\n%d\n" % n)) + 1
    values = []
    for line in body[start:].split("\n"):
        line = line.strip()
        if line == ")":
            break
        if not line:
            continue
        if line.startswith("("):
            values.append(tuple(float(x) for x in line.strip("()").split()))
        else:
            values.append(float(line))
        if len(values) == n:
            break
    return values


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--held", action="store_true", help="the sphere is held (force K U_z, `none`)")
    ap.add_argument("--d", type=float, default=20e-6, help="sphere diameter [m]")
    ap.add_argument("--n-d", type=float, default=2, help="cell size in diameters")
    ap.add_argument("--n-cells", type=int, default=23, help="cells per direction (sphere in the middle one)")
    ap.add_argument("--u-up", type=float, default=1.211111111e-2, help="inflow [m/s]")
    ap.add_argument("--mu", type=float, default=1.8e-5)
    ap.add_argument("--rho", type=float, default=1.2, help="gas density [kg/m3]")
    ap.add_argument("--rho-p", type=float, default=1000.0, help="particle density (free sphere)")
    ap.add_argument("--dt", type=float, default=2e-4, help="coupling interval [s]")
    a = ap.parse_args()

    d, Delta, mu = a.d, a.n_d * a.d, a.mu
    m = a.n_cells // 2
    cell = m + a.n_cells * m + a.n_cells * a.n_cells * m
    eps = 1.0 - np.pi / 6.0 * d ** 3 / Delta ** 3
    eps_f = 0.5 * (1.0 + eps)
    G = C_V / (eps_f * mu * Delta)
    K = 3.0 * np.pi * mu * d
    W = a.rho_p * np.pi / 6.0 * d ** 3 * 9.81 if not a.held else K * a.u_up
    viscous = eps_f * mu / (eps * a.rho) / Delta ** 2

    fluid = os.path.join(a.run, "fluid")
    times = sorted((t for t in os.listdir(fluid) if re.fullmatch(r"[0-9.e+-]+", t) and float(t) > 0),
                   key=float)
    T = np.array([float(t) for t in times])
    Uz = np.array([internal_field(os.path.join(fluid, t, "U"))[cell][2] for t in times])

    steps = int(round(T[-1] / a.dt))
    ends = a.dt * np.arange(1, steps + 1)  # the end of each interval
    if a.held:
        F = K * np.interp(ends, T, Uz)  # K (u_new - 0)
    else:
        with h5py.File(os.path.join(a.run, "particles.h5"), "r") as f:
            snaps = f["snapshots"]
            keys = sorted(snaps.keys())
            ts = np.array([snaps[k].attrs["time"] for k in keys])
            vz = np.array([snaps[k]["velocity"][0, 2] for k in keys])
        if len(ts) < steps + 1 or abs(ts[1] - a.dt) > 1e-12:
            raise SystemExit("disturbance.py: particles.h5 needs one snapshot per coupling step "
                             "(--set output.interval=%g)" % a.dt)
        mass = a.rho_p * np.pi / 6.0 * d ** 3
        F = mass * (np.diff(vz[: steps + 1]) / a.dt + 9.81)

    y = np.zeros(len(MODES))
    H = np.empty(steps)
    for k, Fk in enumerate(F):
        for i, (lam, w) in enumerate(MODES):
            r = lam * viscous * a.dt
            y[i] = (y[i] + r * w * Fk) / (1.0 + r)
        H[k] = y.sum()

    print("cell %d, eps %.5f, G %.6e s/kg, K G %.4f" % (cell, eps, G, K * G))
    print("| t [ms] | d / u_up | F / F_0 | G H / u_up | d / (G H) |")
    print("|---:|---:|---:|---:|---:|")
    for t, u in zip(T, Uz):
        k = int(round(t / a.dt)) - 1
        if k < 0 or k >= steps:
            continue
        dist = a.u_up - u
        print("| %.1f | %.5f | %.5f | %.5f | %.5f |" % (t * 1e3, dist / a.u_up, F[k] / W,
                                                       G * H[k] / a.u_up, dist / (G * H[k])))


if __name__ == "__main__":
    main()
