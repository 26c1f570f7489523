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

    python3 scripts/bed_motion.py RUN --per-snapshot [--after T] [--until T]

One row per snapshot of one run instead: the share not yet coated (coating exactly zero: a
parcel that entered the coating zone took precursor there, open passes included), the mean
coating per parcel and its CV (sample standard deviation), the pressure drop's mean over the time
since the snapshot before, and the parcels faster than 5 mm/s with, of them, those 10-30 mm from
the vertical axis (the ring around a central spout): when and where a fixed bed moves.
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


def per_snapshot(run, after, until):
    snaps = [s for s in snapshots(run)
             if (after is None or s[0] >= after - 1e-12) and (until is None or s[0] <= until + 1e-12)]
    t_dp, dp = [], []
    try:
        for r in csv.DictReader(open(f"{run}/timeseries.csv")):
            if r.get("pressure_drop") and np.isfinite(float(r["pressure_drop"])):
                t_dp.append(float(r["time"]))
                dp.append(float(r["pressure_drop"]))
    except OSError:
        pass
    t_dp, dp = np.array(t_dp), np.array(dp)
    print("| t [s] | not yet coated | mean [ng per parcel] | CV | pressure drop [Pa] | moving "
          "| of them 10-30 mm from the axis |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    before = None
    for t, g in snaps:
        c = np.asarray(g["coating_mass"][:], dtype=float) if "coating_mass" in g else None
        x = g["position"][:].reshape(-1, 3)
        v = np.linalg.norm(g["velocity"][:].reshape(-1, 3), axis=1)
        moving = v > 0.005
        r = np.hypot(x[:, 0], x[:, 1])
        ring = moving & (r >= 0.01) & (r < 0.03)
        window = (t_dp > (before if before is not None else t - 0.1)) & (t_dp <= t + 1e-12)
        p = f"{dp[window].mean():.1f}" if window.any() else "-"
        if c is not None and c.mean() > 0:
            coat = f"{100 * np.mean(c == 0):.2f} % | {1e12 * c.mean():.1f} | {c.std(ddof=1) / c.mean():.2f}"
        else:
            coat = "- | - | -"
        print(f"| {t:.4g} | {coat} | {p} | {moving.sum():,} | {ring.sum():,} |")
        before = t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--after", type=float, help="start of the window [s] (default: skip the first quarter)")
    ap.add_argument("--until", type=float, help="end of the window [s] (default: the last snapshot)")
    ap.add_argument("--per-snapshot", action="store_true", help="one row per snapshot of one run")
    a = ap.parse_args()
    if a.per_snapshot:
        if len(a.runs) != 1:
            sys.exit("bed_motion: --per-snapshot reads one run")
        per_snapshot(a.runs[0], a.after, a.until)
        return
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
