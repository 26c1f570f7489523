#!/usr/bin/python3
"""How much a bed moves: the regime of a fluidized-bed run in numbers.

    python3 scripts/bed_motion.py RUN [RUN ...] [--after T] [--until T]

For every run folder, from RUN/particles.h5 (snapshots) and RUN/timeseries.csv, over the
snapshots at t >= --after (default: the first quarter of the run is skipped):
  - parcel speed: median and 90th percentile, share of parcels faster than 5 cm/s;
  - bed height: 50th and 90th percentile of the parcel height, against the first snapshot;
  - mixing: share of parcels that were ever in the lower/upper half of the bed's initial height
    and later in the other half (vertical exchange), share with coating > 0 at the end of the
    window and the CV of the coating mass there (population standard deviation / mean);
  - pressure drop: mean and relative standard deviation (bubbling beds swing, fixed beds do not).
Prints one Markdown table, one row per run.
"""
import argparse
import csv
import sys

import h5py
import numpy as np


def snapshots(run):
    try:
        f = h5py.File(f"{run}/particles.h5", "r")
    except OSError as e:
        sys.exit(f"bed_motion: cannot read {run}/particles.h5: {e}")
    out = []
    for name, g in f["snapshots"].items():
        if int(g.attrs["count"]) == 0:
            continue
        out.append((float(g.attrs["time"]), g))
    out.sort(key=lambda s: s[0])
    return out


def row(run, after, until=None):
    snaps = snapshots(run)
    if until is not None:
        snaps = [s for s in snaps if s[0] <= until + 1e-12]
    if len(snaps) < 2:
        sys.exit(f"bed_motion: {run} has fewer than two snapshots")
    t_end = snaps[-1][0]
    t_after = after if after is not None else snaps[0][0] + 0.25 * (t_end - snaps[0][0])
    first = snaps[0][1]
    ids0 = first["id"][:]
    z0 = first["position"][:].reshape(-1, 3)[:, 2]
    z_mid = np.median(z0)
    low0 = dict(zip(ids0.tolist(), (z0 < z_mid).tolist()))
    crossed = set()
    speeds, heights = [], []
    for t, g in snaps:
        ids = g["id"][:]
        x = g["position"][:].reshape(-1, 3)
        for i, z in zip(ids.tolist(), x[:, 2].tolist()):
            if i in low0 and low0[i] != (z < z_mid):
                crossed.add(i)
        if t < t_after - 1e-12:
            continue
        v = g["velocity"][:].reshape(-1, 3)
        speeds.append(np.linalg.norm(v, axis=1))
        heights.append(x[:, 2])
    s = np.concatenate(speeds)
    h = np.concatenate(heights)
    last = snaps[-1][1]
    coated = cv = None
    if "coating_mass" in last:
        c = last["coating_mass"][:]
        coated = float(np.mean(c > 0))
        cv = float(np.std(c) / np.mean(c)) if np.mean(c) > 0 else None
    dp = []
    try:
        for r in csv.DictReader(open(f"{run}/timeseries.csv")):
            if r.get("pressure_drop") and t_after <= float(r["time"]) <= t_end + 1e-12:
                v = float(r["pressure_drop"])
                if np.isfinite(v):
                    dp.append(v)
    except OSError:
        pass
    dp = np.array(dp)
    return {
        "run": run,
        "window": f"{t_after:.3g}-{t_end:.3g}",
        "median speed [mm/s]": 1e3 * np.median(s),
        "p90 speed [mm/s]": 1e3 * np.percentile(s, 90),
        "> 5 cm/s [%]": 100 * np.mean(s > 0.05),
        "z50 [mm]": 1e3 * np.median(h),
        "z90 [mm]": 1e3 * np.percentile(h, 90),
        "z90 at start [mm]": 1e3 * np.percentile(z0, 90),
        "crossed mid-height [%]": 100 * len(crossed) / len(ids0),
        "coated [%]": None if coated is None else 100 * coated,
        "coating CV": cv,
        "dp mean [Pa]": float(dp.mean()) if dp.size else None,
        "dp std/mean [%]": 100 * float(dp.std() / dp.mean()) if dp.size else None,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--after", type=float, help="start of the window [s] (default: skip the first quarter)")
    ap.add_argument("--until", type=float, help="end of the window [s] (default: the last snapshot)")
    a = ap.parse_args()
    rows = [row(r, a.after, a.until) for r in a.runs]
    keys = list(rows[0].keys())
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for r in rows:
        cells = []
        for k in keys:
            v = r[k]
            cells.append("-" if v is None else (f"{v:.3g}" if isinstance(v, float) else str(v)))
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
