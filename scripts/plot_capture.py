#!/usr/bin/env python3
"""Where the precursor goes, run by run: the share of the feed taken up by the parcels in each
window of simulated time, and the bed's pressure drop, from each run's timeseries.csv.

usage: plot_capture.py OUT.png RUN[=LABEL] [RUN[=LABEL] ...] [--window SECONDS]

A coating run's captured share rises while the vessel fills with precursor and then settles; the
window share (coated in the window / fed in the window) shows when it has settled, which the
share since the start hides. Prints the table of window shares too.
"""
import argparse
import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(run: Path):
    with open(run / "timeseries.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "coated_mass" not in rows[0]:
        raise SystemExit(f"{run}/timeseries.csv: no coated_mass column (a run without coating)")
    col = {k: [float(r[k]) if r[k] not in ("", "nan") else math.nan for r in rows] for k in rows[0]}
    return col


def windows(col, width):
    t, fed, coated = col["time"], col["precursor_in"], col["coated_mass"]
    out, start = [], 0
    edge = t[0] + width
    for i in range(1, len(t)):
        if t[i] >= edge - 1e-12 or i == len(t) - 1:
            d_in = fed[i] - fed[start]
            if d_in > 0 and t[i] - t[start] > 0.5 * width:
                out.append((t[start], t[i], (coated[i] - coated[start]) / d_in))
            start, edge = i, t[i] + width
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--window", type=float, default=0.1, help="window of simulated time [s]")
    a = ap.parse_args()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    top_dp = 0.0
    for spec in a.runs:
        path, _, label = spec.partition("=")
        col = read(Path(path))
        label = label or Path(path).name
        w = windows(col, a.window)
        xs = [w[0][0]] + [b for _, b, _ in w] if w else []
        ys = [100 * s for _, _, s in w]
        line, = top.step(xs, ys[:1] + ys, where="pre", label=label)
        total = [100 * c / f if f > 0 else math.nan for c, f in zip(col["coated_mass"], col["precursor_in"])]
        top.plot(col["time"], total, ls=":", color=line.get_color())
        bottom.plot(col["time"], col["pressure_drop"], color=line.get_color(), lw=0.6, label=label)
        # the first steps' pressure wave would set the scale: the rest of the run sets it
        late = [p for t, p in zip(col["time"], col["pressure_drop"]) if t > 0.05 and p == p]
        top_dp = max(top_dp, 1.2 * max(late, default=0))
        print(f"{label}: " + ", ".join(f"{a0:.2f}-{b:.2f} s {100 * s:.1f} %" for a0, b, s in w))
    top.set_ylabel(f"taken up / fed [%]\n(steps: per {a.window:g} s; dotted: since the start)")
    top.grid(alpha=0.3)
    top.legend(fontsize=8)
    if top_dp > 0:
        bottom.set_ylim(0, top_dp)
    bottom.set_ylabel("pressure drop [Pa]\n(scale from t > 0.05 s)")
    bottom.set_xlabel("coupled time [s]")
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
