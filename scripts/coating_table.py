#!/usr/bin/python3
"""The coating of a run's parcels at every whole second, computed from particles.h5 alone with
h5py and numpy (independent of cosim's own analysis code, to check `cosim report` against):
mean per parcel, CV (sample standard deviation), CV x sqrt(t), the share never coated (below
1e-6 of the mean), skewness; then the paper's Eqs. 9-10 fitted through the origin on the
seconds up to --fit-until (mean = a1 t, variance = a2^2 t) and their prediction at each later
second beside the simulated value.

  scripts/coating_table.py RUN/particles.h5 [--fit-until 20]

A run in progress can be read: set HDF5_USE_FILE_LOCKING=FALSE (the writer holds the file).
"""
import argparse

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("particles_h5")
    ap.add_argument("--fit-until", type=float, default=20.0,
                    help="last second used for the Eqs. 9-10 fit [s] (default 20)")
    a = ap.parse_args()
    rows = []
    with h5py.File(a.particles_h5, "r") as f:
        for name in sorted(f["snapshots"].keys()):
            g = f["snapshots"][name]
            t = float(g.attrs["time"])
            if t <= 0 or abs(t - round(t)) > 1e-9:
                continue
            m = np.asarray(g["coating_mass"][:], dtype=float)
            mu = m.mean()
            sd = m.std(ddof=1)
            skew = ((m - mu) ** 3).mean() / m.std() ** 3
            rows.append((t, mu, sd * sd, sd / mu, (m <= 1e-6 * mu).mean(), skew))
    print("| t [s] | mean per parcel [ng] | CV | CV x sqrt(t / 1 s) | never coated | skewness |")
    print("|---:|---:|---:|---:|---:|---:|")
    for t, mu, var, cv, never, skew in rows:
        print(f"| {t:.0f} | {mu * 1e12:.1f} | {cv:.3f} | {cv * np.sqrt(t):.3f} | "
              f"{100 * never:.2f} % | {skew:.2f} |")
    fit = [r for r in rows if r[0] <= a.fit_until + 1e-9]
    if len(fit) < 2:
        return
    t = np.array([r[0] for r in fit])
    a1 = (t * np.array([r[1] for r in fit])).sum() / (t * t).sum()
    a2sq = (t * np.array([r[2] for r in fit])).sum() / (t * t).sum()
    print(f"\nEqs. 9-10 through the origin on t <= {a.fit_until:g} s ({len(fit)} seconds): "
          f"a1 = {a1 * 1e12:.2f} ng/s, a2 = {np.sqrt(a2sq) * 1e12:.2f} ng/s^0.5, "
          f"CV(t) = {np.sqrt(a2sq) / a1:.3f} / sqrt(t)")
    print("\n| t [s] | mean: fit / simulated | variance: fit / simulated | CV: fit, simulated |")
    print("|---:|---:|---:|---:|")
    for tt, mu, var, cv, _, _ in rows:
        print(f"| {tt:.0f} | {a1 * tt / mu:.4f} | {a2sq * tt / var:.4f} | "
              f"{np.sqrt(a2sq / tt) / a1:.3f}, {cv:.3f} |")


if __name__ == "__main__":
    main()
