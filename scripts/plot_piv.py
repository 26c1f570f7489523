#!/usr/bin/env python3
"""Plots of `cosim piv` and `cosim piv-compare` (matplotlib, Agg backend).

usage:
  plot_piv.py field PIV_FOLDER
      reads grid.csv and profiles.csv of `cosim piv`, writes PIV_FOLDER/piv.png: the
      time-averaged vertical parcel velocity in the plane of the front wall, with the profile
      heights marked, and the profiles with their standard errors
  plot_piv.py compare SIMULATED_PROFILES MEASURED_PROFILES COMPARISON_CSV OUT_PNG [LABEL LABEL]
      one panel per measured height: the simulated profile (band: +- one standard error) and
      the measured points, the mean absolute errors of COMPARISON_CSV in the panel's title; the
      two labels name them in the legend (default: simulated, measured)
"""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def number(text):
    text = (text or "").strip()
    return float(text) if text else math.nan


def rows(path):
    """The rows of a CSV with a header line, '#' lines and blank lines skipped."""
    with open(path, newline="") as f:
        lines = [line for line in f if line.strip() and not line.lstrip().startswith("#")]
    table = list(csv.reader(lines))
    if not table:
        return []
    head = [h.strip() for h in table[0]]
    return [{h: c.strip() for h, c in zip(head, r)} for r in table[1:]]


def profiles(path):
    """{height_m: (x, vz, stderr)} sorted by x; stderr NaN where the file has none."""
    out = {}
    for r in rows(path):
        h = round(number(r["height_m"]), 9)
        out.setdefault(h, []).append(
            (number(r["x_m"]), number(r["vz_m_s"]), number(r.get("vz_stderr_m_s"))))
    return {h: tuple(np.array(c) for c in zip(*sorted(pts))) for h, pts in sorted(out.items())}


def field(folder: Path) -> int:
    grid = rows(folder / "grid.csv")
    xs = sorted({number(r["x_m"]) for r in grid})
    zs = sorted({number(r["z_m"]) for r in grid})
    vz = np.full((len(zs), len(xs)), np.nan)
    ix = {x: i for i, x in enumerate(xs)}
    iz = {z: i for i, z in enumerate(zs)}
    for r in grid:
        vz[iz[number(r["z_m"])], ix[number(r["x_m"])]] = number(r["vz_m_s"])
    prof = profiles(folder / "profiles.csv")
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 5.5), gridspec_kw={"width_ratios": [1, 1.3]})
    finite = np.abs(vz[np.isfinite(vz)])
    limit = float(np.percentile(finite, 98)) if finite.size else 1.0
    dx = xs[1] - xs[0] if len(xs) > 1 else 1e-3
    dz = zs[1] - zs[0] if len(zs) > 1 else 1e-3
    extent = [1e3 * (xs[0] - dx / 2), 1e3 * (xs[-1] + dx / 2), 1e3 * (zs[0] - dz / 2),
              1e3 * (zs[-1] + dz / 2)]
    image = ax.imshow(np.ma.masked_invalid(vz), origin="lower", extent=extent, aspect="auto",
                      cmap="RdBu_r", vmin=-limit, vmax=limit, interpolation="nearest")
    fig.colorbar(image, ax=ax, label="time-averaged vz [m/s] (blank: no parcel seen)")
    for h in prof:
        ax.axhline(1e3 * h, color="k", lw=0.8, ls="--")
    ax.set_xlabel("x [mm] (across the width, as the camera sees it)")
    ax.set_ylabel("z [mm] (above the bottom)")
    ax.set_title("through the front wall")
    for h, (x, v, se) in prof.items():
        line, = bx.plot(1e3 * x, v, "o-", ms=3, label=f"z = {1e3 * h:g} mm")
        if np.isfinite(se).any():
            bx.fill_between(1e3 * x, v - se, v + se, color=line.get_color(), alpha=0.25, lw=0)
    bx.axhline(0, color="gray", lw=0.6)
    bx.set_xlabel("x [mm]")
    bx.set_ylabel("vz [m/s] (band: +- one standard error)")
    bx.set_title("profiles")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(folder / "piv.png", dpi=110)
    return 0


def compare(simulated: Path, measured: Path, comparison: Path, out: Path,
            labels=("simulated", "measured")) -> int:
    # a name is text, not matplotlib's $math$
    sim_label, meas_label = (label.replace("$", r"\$") for label in labels)
    sim = profiles(simulated)
    meas = profiles(measured)
    errors = {}
    for r in rows(comparison):
        errors[(r["height_m"], r["region"])] = (number(r["mae_m_s"]), number(r["noise_mae_m_s"]))
    heights = list(meas)
    fig, axes = plt.subplots(1, len(heights), figsize=(5.6 * len(heights), 4.8), squeeze=False,
                             sharey=True)
    for ax, h in zip(axes[0], heights):
        key = next((k for k in sim if abs(k - h) <= 1e-6), None)
        if key is not None:
            x, v, se = sim[key]
            ax.plot(1e3 * x, v, "-", color="C0", label=sim_label)
            if np.isfinite(se).any():
                ax.fill_between(1e3 * x, v - se, v + se, color="C0", alpha=0.25, lw=0)
        x, v, se = meas[h]
        ax.errorbar(1e3 * x, v, yerr=np.where(np.isfinite(se), se, 0), fmt="s", ms=4,
                    color="C3", label=meas_label)
        ax.axhline(0, color="gray", lw=0.6)
        title = f"z = {1e3 * h:g} mm"
        hkey = next((k for k, _ in errors if k != "all" and abs(float(k) - h) <= 1e-6), None)
        if hkey is not None:
            parts = {}
            for region in ("all", "core", "sides"):
                mae, noise = errors.get((hkey, region), (math.nan, math.nan))
                if math.isfinite(mae):
                    parts[region] = f"{region} {mae:.3f}" + (
                        f" ({noise:.3f})" if math.isfinite(noise) else "")
            title += "\nmean absolute error [m/s] (from noise alone)"
            if "all" in parts:
                title += "\n" + parts["all"]
            regions = [parts[r] for r in ("core", "sides") if r in parts]
            if regions:
                title += "\n" + ", ".join(regions)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x [mm]")
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("time-averaged vz [m/s]")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


def main(argv) -> int:
    if len(argv) == 3 and argv[1] == "field":
        return field(Path(argv[2]))
    if len(argv) in (6, 8) and argv[1] == "compare":
        return compare(Path(argv[2]), Path(argv[3]), Path(argv[4]), Path(argv[5]),
                       tuple(argv[6:8]) if len(argv) == 8 else ("simulated", "measured"))
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
