#!/usr/bin/python3
"""Side views of a fluidized bed run and its pressure drop over time.

    python3 scripts/plot_bed.py RUN_FOLDER [--times 0.3,0.4,0.5] [-o bed.png]
    python3 scripts/plot_bed.py --compare RUN_A RUN_B ... --times 0.5 -o beds.png

Reads RUN/particles.h5 (one group per snapshot) and RUN/timeseries.csv. Draws the parcels of the
central slab |y| < slab (default: 1.5 parcel diameters) in the x-z plane at up to six snapshots,
so bubbles show as empty regions in the bed, and the bed pressure drop against time below.
With --compare, one side view per run at the first of --times (default: each run's last
snapshot), side by side, each titled with its run folder's name. With --coating the parcels are
coloured by their coating mass relative to the bed's mean at that time (never-coated parcels,
at most 1e-6 of the mean as in cosim report, in grey): which parts of the bed the coating zone
reaches (the paper's Fig. 7). With --speed they are coloured by their speed instead (log scale,
0.1 to 100 mm/s): which parts of the bed move. --zmax fixes the height shown; --dp-from starts the
pressure-drop panel later (past the start-up's spike), marking the snapshots shown.
"""
import argparse
import csv
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


COATING_MAX = 3.0  # colour scale of --coating: 0 to 3 times the bed's mean coating


def side_view(ax, g, slab, title, coating=False, speed=False, zmax=None):
    x = g["position"][:].reshape(-1, 3)
    r = g["radius"][:]
    d = 2 * float(np.median(r))
    sel = np.abs(x[:, 1]) < slab * d
    size = (72 * d * 1e3 / 25.4 * 2.2) ** 2 / 4
    mappable = None
    if coating and "coating_mass" in g:
        m = np.asarray(g["coating_mass"][:], dtype=float)
        mean = m.mean()
        rel = m / mean if mean > 0 else np.zeros_like(m)
        uncoated = m <= 1e-6 * mean if mean > 0 else np.ones(m.shape, dtype=bool)
        never, coated = sel & uncoated, sel & ~uncoated
        ax.scatter(x[never, 0] * 1e3, x[never, 2] * 1e3, s=size, c="0.75", edgecolors="none")
        mappable = ax.scatter(x[coated, 0] * 1e3, x[coated, 2] * 1e3, s=size, c=rel[coated],
                              cmap="viridis", vmin=0, vmax=COATING_MAX, edgecolors="none")
        title += f"\n{100 * uncoated.mean():.0f} % never coated" if mean > 0 else "\nnone coated"
    elif speed and "velocity" in g:
        v = np.linalg.norm(g["velocity"][:].reshape(-1, 3), axis=1) * 1e3
        order = np.argsort(v[sel])  # the moving parcels drawn last, on top
        xs, vs = x[sel][order], v[sel][order]
        mappable = ax.scatter(xs[:, 0] * 1e3, xs[:, 2] * 1e3, s=size, c=np.clip(vs, 0.1, 100),
                              cmap="magma_r", norm=matplotlib.colors.LogNorm(0.1, 100),
                              edgecolors="none")
        title += f"\n{100 * (v > 5).mean():.1f} % faster than 5 mm/s"
    else:
        ax.scatter(x[sel, 0] * 1e3, x[sel, 2] * 1e3, s=size, c="tab:brown", edgecolors="none")
    ax.set_aspect("equal")
    ax.set_xlim(x[:, 0].min() * 1e3 - d * 1e3, x[:, 0].max() * 1e3 + d * 1e3)
    ax.set_ylim(0, zmax if zmax else max(np.percentile(x[:, 2], 99.9) * 1e3 * 1.3, 10))
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x [mm]")
    return mappable


def colorbar(fig, axes, mappable, speed=False):
    if mappable is not None:
        bar = fig.colorbar(mappable, ax=axes, shrink=0.6, pad=0.02)
        bar.set_label("speed [mm/s]" if speed else "coating / bed mean (grey: never coated)")


def compare(runs, times, slab, output, coating=False):
    fig, axes = plt.subplots(1, len(runs), figsize=(2.4 * len(runs) + (1.2 if coating else 0), 6),
                             squeeze=False)
    mappable = None
    for k, run in enumerate(runs):
        try:
            f = h5py.File(f"{run}/particles.h5", "r")
        except OSError as e:
            sys.exit(f"plot_bed: cannot read {run}/particles.h5: {e}")
        snaps = sorted((float(g.attrs["time"]), g) for g in f["snapshots"].values() if int(g.attrs["count"]) > 0)
        if not snaps:
            sys.exit(f"plot_bed: {run}/particles.h5 has no snapshot with particles")
        t, g = min(snaps, key=lambda s: abs(s[0] - times[0])) if times else snaps[-1]
        mappable = side_view(axes[0, k], g, slab, f"{run.rstrip('/').split('/')[-1]}, t = {t:.2f} s",
                             coating) or mappable
    axes[0, 0].set_ylabel("z [mm]")
    fig.suptitle(f"parcels with |y| < {slab:g} d (side view)", fontsize=10)
    if coating:
        colorbar(fig, axes[0, :].tolist(), mappable)
    else:
        fig.tight_layout()
    out = output or "beds.png"
    fig.savefig(out, dpi=110)
    print(f"plot_bed: wrote {out}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", nargs="+")
    ap.add_argument("--compare", action="store_true", help="one side view per run, side by side")
    ap.add_argument("--times", help="snapshot times [s], comma separated (default: six across the run)")
    ap.add_argument("--slab", type=float, default=1.5, help="half thickness of the slab in parcel diameters")
    ap.add_argument("--coating", action="store_true",
                    help="colour the parcels by their coating (grey: never coated)")
    ap.add_argument("--speed", action="store_true", help="colour the parcels by their speed")
    ap.add_argument("--zmax", type=float, help="height shown [mm] (default: to the highest parcels)")
    ap.add_argument("--dp-from", type=float, help="pressure drop shown from this time [s]")
    ap.add_argument("-o", "--output", help="PNG file (default RUN/bed.png)")
    a = ap.parse_args()
    if a.compare:
        compare(a.run, [float(t) for t in a.times.split(",")] if a.times else None, a.slab, a.output,
                a.coating)
        return
    if len(a.run) != 1:
        sys.exit("plot_bed: one run folder, or several with --compare")
    a.run = a.run[0]
    try:
        f = h5py.File(f"{a.run}/particles.h5", "r")
    except OSError as e:
        sys.exit(f"plot_bed: cannot read {a.run}/particles.h5: {e}")
    snaps = [(float(g.attrs["time"]), name) for name, g in f["snapshots"].items() if int(g.attrs["count"]) > 0]
    snaps.sort()
    if not snaps:
        sys.exit(f"plot_bed: {a.run}/particles.h5 has no snapshot with particles")
    if a.times:
        want = [float(t) for t in a.times.split(",")]
    else:
        t0, t1 = snaps[0][0], snaps[-1][0]
        want = list(np.linspace(t0 + 0.5 * (t1 - t0), t1, 6))
    chosen = []
    for t in want:
        best = min(snaps, key=lambda s: abs(s[0] - t))
        if best not in chosen:
            chosen.append(best)
    # A bed wider than the height shown (--zmax): the views three to a row, each wide enough to read
    cols = min(3, len(chosen)) if a.zmax else len(chosen)
    view_rows = -(-len(chosen) // cols)
    if a.zmax:
        fig = plt.figure(figsize=(5.0 * cols, 3.1 * view_rows + 2.7))
    else:
        fig = plt.figure(figsize=(2.2 * len(chosen), 7.5))
    grid = fig.add_gridspec(view_rows + 1, cols,
                            height_ratios=[2.6 if a.zmax else 3] * view_rows + [1.6 if a.zmax else 1])
    for k, (t, name) in enumerate(chosen):
        ax = fig.add_subplot(grid[k // cols, k % cols])
        mappable = side_view(ax, f["snapshots"][name], a.slab, f"t = {t:.3f} s", a.coating,
                             a.speed, a.zmax)
        if (a.coating or a.speed) and k == len(chosen) - 1:
            colorbar(fig, ax, mappable, a.speed and not a.coating)
        if k % cols == 0:
            ax.set_ylabel("z [mm]")
    rows = list(csv.DictReader(open(f"{a.run}/timeseries.csv")))
    if rows and "pressure_drop" in rows[0]:
        ax = fig.add_subplot(grid[view_rows, :])
        keep = [r for r in rows if r["pressure_drop"] not in ("", "nan")
                and (a.dp_from is None or float(r["time"]) >= a.dp_from)]
        t = [float(r["time"]) for r in keep]
        dp = [float(r["pressure_drop"]) for r in keep]
        ax.plot(t, dp, lw=0.6)
        if a.dp_from is not None:
            for ts, _ in chosen:
                ax.axvline(ts, color="0.5", lw=0.8, ls=":")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("bed pressure drop [Pa]")
        ax.grid(alpha=0.3)
    fig.suptitle(f"{a.run}: parcels with |y| < {a.slab:g} d (side view)", fontsize=10)
    fig.tight_layout()
    out = a.output or f"{a.run}/bed.png"
    fig.savefig(out, dpi=110)
    print(f"plot_bed: wrote {out}")


if __name__ == "__main__":
    main()
