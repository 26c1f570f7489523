#!/usr/bin/env python3
"""Plots of `cosim ft4 energy` and `cosim ft4 calibrate` (matplotlib, Agg backend).

usage:
  plot_ft4.py energy PROFILE_CSV [PROFILE_CSV...] OUT_PNG
      the energy gradient M / (R tan alpha) + F and the cumulative flow energy against the
      blade's height (the rows of `cosim ft4 energy`'s profile CSV); several profiles (runs of a
      study, say) are drawn over each other, each named by its file (or its run folder when the
      file is the default ft4_energy.csv)
  plot_ft4.py calibration CALIBRATION_JSON OUT_PNG
      the runs' energies against the parameter, the fitted line, the measured energy with its
      standard error and the value read back through the line
"""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_profile(profile_csv):
    with open(profile_csv, newline="") as f:
        data = list(csv.DictReader(f))
    h = [1e3 * float(r["height_m"]) for r in data]
    g = [float(r["gradient_J_per_m"]) for r in data]  # J/m = mJ/mm
    w = [1e3 * float(r["energy_J"]) for r in data]
    return h, g, w


def label_of(profile_csv):
    p = Path(profile_csv)
    return p.parent.name if p.name == "ft4_energy.csv" else p.stem


def energy(profile_csvs, out_png) -> int:
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(9, 4.5), sharey=True)
    titles = []
    for k, path in enumerate(profile_csvs):
        h, g, w = read_profile(path)
        total = w[-1] if w else 0.0
        label = f"{label_of(path)}: {total:.4g} mJ" if len(profile_csvs) > 1 else None
        ax.plot(g, h, "-", lw=1, color=f"C{k}", label=label)
        bx.plot(w, h, "-", lw=1.5, color=f"C{k}", label=label)
        if h:
            titles.append(f"flow energy {total:.4g} mJ from {max(h):.4g} down to {min(h):.4g} mm")
    ax.set_xlabel("energy gradient M / (R tan alpha) + F [mJ/mm]")
    ax.set_ylabel("blade height above the base [mm]")
    ax.axvline(0, color="gray", lw=0.6)
    bx.set_xlabel("flow energy from the top [mJ]")
    if len(profile_csvs) > 1:
        bx.legend(fontsize=8)
    else:
        fig.suptitle(titles[0] if titles else "no rows")
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)
    return 0


def calibration(calibration_json, out_png) -> int:
    with open(calibration_json) as f:
        c = json.load(f)
    name = c["parameter_name"]
    xs = [p["parameter"] for p in c["points"]]
    ys = [1e3 * p["energy_J"] for p in c["points"]]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.plot(xs, ys, "o", label="simulated runs")
    lo = min(xs + [c["parameter"]])
    hi = max(xs + [c["parameter"]])
    pad = 0.05 * (hi - lo)
    line_x = [lo - pad, hi + pad]
    ax.plot(line_x, [1e3 * (c["intercept_J"] + c["slope_J"] * x) for x in line_x], "-",
            color="gray", lw=1,
            label=f"fit W = {1e3 * c['intercept_J']:.4g} + {1e3 * c['slope_J']:.4g} x {name} mJ")
    m, mse = 1e3 * c["measured_J"], 1e3 * c["measured_se_J"]
    ax.axhline(m, color="C3", lw=1, label=f"measured {m:.4g} mJ")
    if mse > 0:
        ax.axhspan(m - mse, m + mse, color="C3", alpha=0.15, lw=0)
    ax.axvline(c["parameter"], color="C2", lw=1, ls="--",
               label=f"{name} = {c['parameter']:.3g} +- {c['sigma']:.2g}"
               + (" (extrapolated)" if c["extrapolated"] else ""))
    ax.axvspan(c["parameter"] - c["sigma"], c["parameter"] + c["sigma"], color="C2", alpha=0.12,
               lw=0)
    if c.get("bracketed") is not None:
        # the runs' mean energies joined in the parameter's order, and the measurement read
        # between the two that bracket it
        means = {}
        for x, y in zip(xs, ys):
            means.setdefault(x, []).append(y)
        mx = sorted(means)
        ax.plot(mx, [sum(means[x]) / len(means[x]) for x in mx], ":", color="C1", lw=1)
        ax.axvline(c["bracketed"], color="C1", lw=1, ls=":",
                   label=f"between the bracketing runs: {c['bracketed']:.3g}"
                   + (" (the energy bends)" if c.get("bends") else ""))
    ax.set_xlabel(name)
    ax.set_ylabel("flow energy [mJ]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)
    return 0


def main(argv) -> int:
    if len(argv) >= 4 and argv[1] == "energy":
        return energy(argv[2:-1], argv[-1])
    if len(argv) == 4 and argv[1] == "calibration":
        return calibration(argv[2], argv[3])
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
