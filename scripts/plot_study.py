#!/usr/bin/env python3
"""Plot of a `cosim study`: error of each observable against wall time, Pareto front marked.

usage: plot_study.py STUDY_FOLDER   (reads study.json, writes error_vs_runtime.png)
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(folder: Path) -> int:
    study = json.loads((folder / "study.json").read_text())
    rows = [r for r in study["variants"] if r["ok"]]
    names = list(study["references"].keys())
    fig, ax = plt.subplots(figsize=(7, 4.5))
    markers = "os^Dvx*"
    for k, name in enumerate(names):
        pts = [(r["wall_s"], r["observables"][name].get("error"), r["label"], r["pareto"]) for r in rows
               if "error" in r["observables"].get(name, {})]
        if not pts:
            continue
        floor = min((e for _, e, _, _ in pts if e > 0), default=1e-16) / 10
        xs = [p[0] for p in pts]
        ys = [max(p[1], floor) for p in pts]
        ax.scatter(xs, ys, marker=markers[k % len(markers)], label=f"{name} (ref: {study['references'][name]})")
        for x, y, (_, _, label, _) in zip(xs, ys, pts):
            ax.annotate(label, (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
        front = sorted((x, y) for x, y, p in zip(xs, ys, pts) if p[3])
        if len(front) > 1:
            ax.plot([f[0] for f in front], [f[1] for f in front], "--", lw=1, color="gray")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run [s]")
    ax.set_ylabel("relative error")
    ax.set_title("error against run time (dashed: Pareto front)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(folder / "error_vs_runtime.png", dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1])))
