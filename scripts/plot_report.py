#!/usr/bin/env python3
"""Draw the PNG figures of a cosim coating report.

Usage: plot_report.py FOLDER

FOLDER holds either report.json (one run, written by `cosim report`) or comparison.json (several
runs). Every number is computed in C++ (cosim_analysis) and read from those files; this script
only draws. Matplotlib with the Agg backend (no display needed). See docs/analysis.md.
"""
import json
import math
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

def num(values):
    """JSON list (null for non-finite) -> float array with NaN."""
    return np.array([math.nan if v is None else float(v) for v in values], dtype=float)


def save(fig, folder, name):
    fig.tight_layout()
    fig.savefig(os.path.join(folder, name), dpi=110)
    plt.close(fig)
    print("wrote", name)


def normal_pdf(x, mean, sigma):
    return np.exp(-0.5 * ((x - mean) / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))


def scale_for(values_kg):
    """Unit for a coating-mass axis so the largest value reads between 1 and 1000: (factor, label)."""
    values = np.asarray(values_kg, dtype=float)
    m = np.nanmax(np.abs(values)) if values.size and np.isfinite(values).any() else 0.0
    for factor, unit in ((1.0, "kg"), (1e3, "g"), (1e6, "mg"), (1e9, "µg"), (1e12, "ng"), (1e15, "pg")):
        if m * factor >= 1.0:
            return factor, unit
    return 1e15, "pg"


def mass_unit(r, values_kg=None):
    """The report's one unit for coating mass (report.json / comparison.json "units"): (factor, name).
    Older files without it: the unit in which values_kg read between 1 and 1000."""
    u = r.get("units")
    if u and u.get("mass_kg"):
        return 1.0 / u["mass_kg"], u["mass"]
    return scale_for(values_kg if values_kg is not None else np.array([0.0]))


def plot_histograms(r, folder):
    hs = r["histograms"]
    if not hs:
        return
    fig, axes = plt.subplots(1, len(hs), figsize=(3.6 * len(hs), 3.2), squeeze=False)
    allmax = [h["max"] for h in hs if h.get("max") is not None]
    f, unit = mass_unit(r, num(allmax))
    for ax, h in zip(axes[0], hs):
        edges = num(h["edges"]) * f
        counts = np.array(h["counts"], dtype=float)
        n = counts.sum()
        widths = np.diff(edges)
        density = counts / (n * widths) if n > 0 else counts
        ax.bar(edges[:-1], density, width=widths, align="edge", color="#7fa7d9", edgecolor="#2c5d9b", lw=0.5)
        mean, std = h.get("mean"), h.get("std")
        if mean is not None and std is not None and std > 0:
            x = np.linspace(edges[0], edges[-1], 200)
            ax.plot(x, normal_pdf(x, mean * f, std * f), "r-", lw=1.2, label="normal, same mean/σ")
        cv = h.get("cv")
        ax.set_title("t = %.3g s, CV = %s" % (h["time"], "–" if cv is None else "%.3f" % cv), fontsize=9)
        ax.set_xlabel("coating mass per parcel [%s]" % unit)
        ax.set_ylabel("probability density [1/%s]" % unit)
        ax.text(0.98, 0.95, "never coated: %.1f %%" % (100 * (h.get("uncoated_share") or 0)),
                transform=ax.transAxes, ha="right", va="top", fontsize=8)
    axes[0][0].legend(fontsize=7, loc="upper left")
    save(fig, folder, "histograms.png")


def plot_statistics_time(r, folder):
    s = r["snapshots"]
    t = num(s["time"])
    mean = num(s["mean"])
    f, unit = mass_unit(r, mean)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.3))
    axes[0].plot(t, mean * f, "b.-", ms=3, label="mean")
    low = mean - num(s["std"])
    clipped = bool((low < 0).any())  # a skewed (poorly mixed) distribution: no negative coating
    axes[0].fill_between(t, np.maximum(low, 0) * f, (mean + num(s["std"])) * f, color="b", alpha=0.15,
                         label="± σ (cut at 0)" if clipped else "± σ")
    axes[0].set_ylabel("coating mass per parcel [%s]" % unit)
    axes[0].legend(fontsize=8)
    axes[1].plot(t, num(s["cv"]), "k.-", ms=3)
    axes[1].set_ylabel("CV [-]")
    axes[2].plot(t, 100 * num(s["uncoated_share"]), "r.-", ms=3)
    axes[2].set_ylabel("never-coated parcels [%]")
    for ax in axes:
        ax.set_xlabel("time [s]")
        ax.grid(alpha=0.3)
    save(fig, folder, "statistics_time.png")


def plot_cv_mean(r, folder):
    s = r["snapshots"]
    mean = num(s["mean"])
    f, unit = mass_unit(r, mean)
    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.plot(mean * f, num(s["cv"]), "k.-", ms=3)
    ax.set_xlabel("mean coating mass per parcel [%s]" % unit)
    ax.set_ylabel("CV [-]")
    ax.set_title("CV against mean coated mass (paper Fig. 8)", fontsize=9)
    ax.grid(alpha=0.3)
    save(fig, folder, "cv_mean.png")


def plot_fit(r, folder):
    fit = r["fit"]
    s = r["snapshots"]
    t = num(s["time"])
    t0c = fit["coating_start"] or 0.0
    mean = num(s["mean"])
    sd = num(s["std"])
    f, unit = mass_unit(r, mean)
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.5))
    axes[0].plot(t, mean * f, "b.", ms=4, label="simulated")
    # Eq. 10 fits the variance a2^2 t; drawn as the standard deviation a2 sqrt(t), in the page's unit.
    axes[1].plot(t, sd * f, "g.", ms=4, label="simulated")
    if fit["ok"]:
        tt = np.linspace(max(t0c, 0.0), max(t.max(), fit["t1"]), 200)
        tau = tt - t0c
        a1, a2 = fit["a1"], fit["a2"]
        axes[0].plot(tt, a1 * tau * f, "r-",
                     label="a1 t, a1 = %.4g ± %.2g %s/s" % (a1 * f, fit["a1_error"] * f, unit))
        axes[1].plot(tt, a2 * np.sqrt(tau) * f, "r-",
                     label="a2 √t, a2 = %.4g ± %.2g %s/s^0.5" % (a2 * f, fit["a2_error"] * f, unit))
        tf = num(fit["time"])
        rm = num(fit["mean_residual"]) / np.maximum(num(fit["mean"]), 1e-300)
        rv = num(fit["variance_residual"]) / np.maximum(num(fit["variance"]), 1e-300)
        axes[2].plot(tf, 100 * rm, "b.-", ms=4, label="mean")
        axes[2].plot(tf, 100 * rv, "g.-", ms=4, label="variance")
        axes[2].axhline(0, color="k", lw=0.8)
    else:
        axes[2].text(0.5, 0.5, "no fit:\n" + fit["problem"], ha="center", va="center", wrap=True,
                     transform=axes[2].transAxes, fontsize=8)
    for ax in axes[:2]:
        ax.axvspan(fit["t0"], fit["t1"], color="orange", alpha=0.12, label="fit window")
        ax.set_xlabel("time [s]")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("mean coating mass [%s]" % unit)
    axes[1].set_ylabel("standard deviation [%s]" % unit)
    axes[2].set_xlabel("time [s]")
    axes[2].set_ylabel("residual / data [%]")
    axes[2].set_title("residuals of the fit (paper Fig. 10E)", fontsize=9)
    axes[2].legend(fontsize=7)
    axes[2].grid(alpha=0.3)
    save(fig, folder, "fit.png")


def plot_cv_prediction(r, folder):
    p = r["cv_prediction"]
    if not p["tau"]:
        return
    tau = num(p["tau"]) / 60.0
    fig, ax = plt.subplots(figsize=(6, 3.8))
    ax.fill_between(tau, num(p["cv_low"]), num(p["cv_high"]), color="#7fa7d9", alpha=0.4,
                    label="a2 ± %.0f %%" % (100 * p["band"]))
    ax.plot(tau, num(p["cv"]), "b-", label="(a2/a1)/√t")
    s = r["snapshots"]
    t = (num(s["time"]) - (r["fit"]["coating_start"] or 0.0)) / 60.0
    ok = t > 0
    ax.plot(t[ok], num(s["cv"])[ok], "k.", ms=3, label="simulated")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("coating time [min]")
    ax.set_ylabel("CV [-]")
    ax.set_title("CV prediction (paper Fig. 11)", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    save(fig, folder, "cv_prediction.png")


def refusal_text(r, width=95):
    lines = ["Extrapolation refused (poorly mixed):"]
    for reason in r["verdict"]["reasons"]:
        lines += textwrap.wrap("• " + reason, width=width, subsequent_indent="   ")
    return "\n".join(lines)


def figure_with_note(note, figsize=(7.5, 4.2)):
    """A figure with one plot and, under it, a panel holding `note` (wrapped text)."""
    n_lines = note.count("\n") + 1
    fig = plt.figure(figsize=(figsize[0], figsize[1] + 0.16 * n_lines))
    gs = fig.add_gridspec(2, 1, height_ratios=[figsize[1], 0.16 * n_lines + 0.1])
    ax = fig.add_subplot(gs[0])
    box = fig.add_subplot(gs[1])
    box.axis("off")
    box.text(0.0, 1.0, note, fontsize=7.5, va="top", ha="left", family="sans-serif",
             bbox=dict(facecolor="#fde8e8", edgecolor="#a11"))
    return fig, ax


def plot_refused_prediction(r, folder):
    """Poorly mixed run: the simulated CV with the fitted trend over the simulated times only,
    and why there is no prediction (no extrapolation is drawn)."""
    s = r["snapshots"]
    fit = r["fit"]
    t0c = fit["coating_start"] or 0.0
    t = num(s["time"]) - t0c
    cv = num(s["cv"])
    ok = (t > 0) & np.isfinite(cv)
    fig, ax = figure_with_note(refusal_text(r))
    ax.plot(t[ok], cv[ok], "k.-", ms=4, label="simulated CV")
    if fit["ok"] and ok.any():
        tt = np.linspace(t[ok].min(), t[ok].max(), 100)
        ax.plot(tt, (fit["a2"] / fit["a1"]) / np.sqrt(tt), "b--", lw=1,
                label="(a2/a1)/√t on the simulated window only")
    ax.set_xlabel("coating time [s]")
    ax.set_ylabel("CV [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("CV: no prediction for a poorly mixed run (paper Fig. 11)", fontsize=9)
    save(fig, folder, "cv_prediction.png")


def plot_refused_distributions(r, folder):
    """Poorly mixed run: the last simulated histogram instead of reconstructed distributions."""
    hs = r["histograms"]
    fig, ax = figure_with_note("No reconstructed distributions.\n" + refusal_text(r))
    if hs and hs[-1]["counts"]:
        h = hs[-1]
        f, unit = mass_unit(r, num([h["max"]]))
        edges = num(h["edges"]) * f
        ax.bar(edges[:-1], h["counts"], width=np.diff(edges), align="edge", color="#7fa7d9", edgecolor="#2c5d9b",
               lw=0.5, label="simulated, t = %.3g s" % h["time"])
        ax.set_xlabel("coating mass per parcel [%s]" % unit)
        ax.set_ylabel("parcels")
        ax.legend(fontsize=8, loc="upper right")
    ax.set_title("distributions: not reconstructed for a poorly mixed run (paper Fig. 12)", fontsize=9)
    save(fig, folder, "distributions.png")


def plot_distributions(r, folder):
    ds = r["distributions"]
    if not ds:
        return
    f, unit = mass_unit(r, num([d["mean"] + 4 * d["sigma"] for d in ds]))
    fig, ax = plt.subplots(figsize=(6, 3.8))
    for d in ds:
        x = np.linspace(max(0.0, d["mean"] - 4.5 * d["sigma_high"]), d["mean"] + 4.5 * d["sigma_high"], 300)
        line, = ax.plot(x * f, normal_pdf(x, d["mean"], d["sigma"]) / f,
                        label="%.3g min: CV = %.3f" % (d["tau"] / 60.0, d["cv"]))
        ax.fill_between(x * f, normal_pdf(x, d["mean"], d["sigma_low"]) / f,
                        normal_pdf(x, d["mean"], d["sigma_high"]) / f, color=line.get_color(), alpha=0.15)
    ax.set_xlabel("coating mass per parcel [%s]" % unit)
    ax.set_ylabel("probability density [1/%s]" % unit)
    ax.set_title("reconstructed distributions (paper Fig. 12)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    save(fig, folder, "distributions.png")


def read_csv(path):
    with open(path) as fh:
        header = fh.readline().strip().split(",")
        rows = []
        for line in fh:
            cells = line.strip().split(",")
            if len(cells) != len(header):
                continue
            try:
                rows.append([float(c) for c in cells])
            except ValueError:
                continue
    data = np.array(rows, dtype=float).reshape(-1, len(header))
    return {h: data[:, i] for i, h in enumerate(header)}


def plot_mass_balance(r, folder):
    ts_path = os.path.join(r["run"], "timeseries.csv")
    if r.get("mass_balance") is None or not os.path.exists(ts_path):
        return
    ts = read_csv(ts_path)
    need = ("time", "precursor_in", "precursor_out", "precursor_held", "coated_mass")
    if any(k not in ts for k in need) or len(ts["time"]) == 0:
        return
    mb = r["mass_balance"]
    t = ts["time"]
    initial = ts["precursor_in"][0] == 0.0 and ts["precursor_out"][0] == 0.0
    cin = ts["precursor_in"] - (ts["precursor_in"][0] if initial else 0.0)  # cumulative columns
    cout = ts["precursor_out"] - (ts["precursor_out"][0] if initial else 0.0)
    held = ts["precursor_held"] - mb["held_start"]
    coated = ts["coated_mass"] - mb["coated_start"]
    f, unit = mass_unit(r, np.array([cin.max()]))
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.6))
    axes[0].plot(t, cin * f, label="in")
    axes[0].plot(t, cout * f, label="out")
    axes[0].plot(t, held * f, label="held in gas (change)")
    axes[0].plot(t, (cin - cout - held) * f, "k--", label="expected coating")
    axes[0].plot(t, coated * f, "r:", lw=2, label="coating credited to particles")
    axes[0].set_xlabel("time [s]")
    axes[0].set_ylabel("cumulative precursor [%s]" % unit)
    axes[0].legend(fontsize=8)
    axes[0].grid(alpha=0.3)
    err = (cin - cout - held) - coated
    axes[1].plot(t, err * f, "k-", label="expected − credited")
    if "precursor_removed" in ts:
        removed = ts["precursor_removed"] - (ts["precursor_removed"][0] if initial else 0.0)
        axes[1].plot(t, ((cin - cout - held) - removed) * f, "g-", label="expected − removed by the sink")
    axes[1].legend(fontsize=7)
    axes[1].set_xlabel("time [s]")
    axes[1].set_ylabel("expected − credited [%s]" % unit)
    axes[1].set_title("expected − credited over time (a step's removal is credited one step later)\n"
                      "final mass balance error: %.3g %%" % (mb["error_percent"] or 0.0), fontsize=8)
    axes[1].grid(alpha=0.3)
    save(fig, folder, "mass_balance.png")


def plot_window_study(r, folder):
    w = r.get("window_study")
    if not w or not w["points"]:
        return
    pts = [p for p in w["points"] if p["ok"]]
    if len(pts) < 2:
        return
    wall = num([p["wall_seconds"] for p in pts])
    use_wall = np.isfinite(wall).all() and wall[-1] > 0
    x = wall if use_wall else num([p["t_end"] for p in pts])
    xlabel = "wall time to simulate the window [s]" if use_wall else "end of the fit window [s]"
    # A poorly mixed run: no extrapolated CV (it would contradict the verdict), only how well
    # shorter windows predict the simulated CV at the run's end.
    extrapolate = r["verdict"]["well_mixed"]
    fig, axes = plt.subplots(1, 2 if extrapolate else 1, figsize=(11 if extrapolate else 6, 3.6), squeeze=False)
    axes = axes[0]
    if extrapolate:
        axes[0].plot(x, num([p["cv_horizon"] for p in pts]), "bo-", ms=4)
        axes[0].set_ylabel("extrapolated CV at %.3g min" % (w["horizon"] / 60.0))
    err_ax = axes[-1]
    err = num([p["cv_run_end_error"] for p in pts])
    ok = np.isfinite(err)
    if ok.any():
        err_ax.plot(x[ok], 100 * np.abs(err[ok]), "ro-", ms=4)
        err_ax.set_ylim(bottom=0)
    err_ax.set_ylabel("|error| of the CV predicted at t = %.3g s [%%]" % w["run_end"])
    if not extrapolate:
        err_ax.set_title("poorly mixed: no extrapolated CV", fontsize=9)
    for ax in axes:
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3, which="both")
    save(fig, folder, "window_study.png")


def plot_zone_passes(r, folder):
    """Histograms of passes per parcel, cycle time and pass duration (zone_passes in report.json)."""
    z = r.get("zone_passes") or {}
    if not z.get("recorded"):
        return
    panels = [("passes_per_parcel", "passes through the zone per parcel", 1.0, ""),
              ("cycle_time_s", "cycle time (entry to next entry)", 1e3, "ms"),
              ("pass_duration_s", "time in the zone per pass", 1e3, "ms")]
    panels = [p for p in panels if z[p[0]]["n"] > 0 and z[p[0]]["counts"]]
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(3.8 * len(panels), 3.2), squeeze=False)
    for ax, (key, label, f, unit) in zip(axes[0], panels):
        d = z[key]
        edges = num(d["edges"]) * f
        counts = np.array(d["counts"], dtype=float)
        ax.bar(edges[:-1], counts, width=np.diff(edges), align="edge", color="#9fcf8f",
               edgecolor="#3b7a2a", lw=0.5)
        ax.set_xlabel(label + (" [%s]" % unit if unit else ""))
        ax.set_ylabel("parcels" if key == "passes_per_parcel" else "count")
        mean = d.get("mean")
        if mean is not None:
            ax.axvline(mean * f, color="r", lw=1.0)
            ax.set_title("mean %.3g%s, n = %d" % (mean * f, " " + unit if unit else "", d["n"]), fontsize=9)
    if z.get("never_entered_share") is not None:
        axes[0][0].text(0.98, 0.95, "never in the zone: %.1f %%" % (100 * z["never_entered_share"]),
                        transform=axes[0][0].transAxes, ha="right", va="top", fontsize=8)
    save(fig, folder, "zone_passes.png")


def run_report(folder):
    with open(os.path.join(folder, "report.json")) as fh:
        r = json.load(fh)
    plot_histograms(r, folder)
    plot_statistics_time(r, folder)
    plot_cv_mean(r, folder)
    plot_fit(r, folder)
    if r["verdict"]["well_mixed"]:
        plot_cv_prediction(r, folder)
        plot_distributions(r, folder)
    else:  # same figures, but no extrapolation in them: they say why
        plot_refused_prediction(r, folder)
        plot_refused_distributions(r, folder)
    plot_window_study(r, folder)
    plot_mass_balance(r, folder)
    plot_zone_passes(r, folder)


def plot_side_by_side(reports, f, unit, folder):
    """One column per run with its verdict: CV over time, CV against mean coating (Fig. 8), and the
    growth of mean and standard deviation with the fit of Eqs. 9-10 (Fig. 10), rows sharing axes."""
    n = len(reports)
    fig, axes = plt.subplots(4, n, figsize=(3.3 * n, 10.5), squeeze=False, sharey="row")
    for k, (run, r) in enumerate(reports):
        s = r["snapshots"]
        fit = r["fit"]
        t = num(s["time"])
        mean, sd, cv = num(s["mean"]), num(s["std"]), num(s["cv"])
        ok = np.isfinite(cv)
        well = run["well_mixed"]
        colour = "#186a1e" if well else "#a11"
        col = axes[:, k]
        cond = run.get("conditions") or {}
        lines = [run["label"]]
        if cond.get("flow_lpm") is not None:
            lines.append("%.4g L/min" % cond["flow_lpm"] + (
                ", u/u_mf = %.2g" % cond["u_over_umf"] if cond.get("u_over_umf") is not None else ""))
        lines.append(run.get("verdict_short", "well mixed" if well else "poorly mixed"))
        col[0].set_title("\n".join(lines), fontsize=9, color=colour)
        col[0].plot(t[ok], cv[ok], "k.-", ms=3)
        col[0].set_xlabel("time [s]")
        col[1].plot(mean[ok] * f, cv[ok], "k.-", ms=3)
        col[1].set_xlabel("mean coating per parcel [%s]" % unit)
        col[2].plot(t, mean * f, "b.", ms=3, label="simulated")
        col[3].plot(t, sd * f, "g.", ms=3, label="simulated")
        if fit["ok"]:
            t0c = fit["coating_start"] or 0.0
            tt = np.linspace(max(t0c, float(np.nanmin(t))), float(np.nanmax(t)), 100)
            tau = np.maximum(tt - t0c, 0.0)
            col[2].plot(tt, fit["a1"] * tau * f, "r-", lw=1, label="a1 t")
            col[3].plot(tt, fit["a2"] * np.sqrt(tau) * f, "r-", lw=1, label="a2 √t")
        for ax in col[2:]:
            ax.set_xlabel("time [s]")
            ax.legend(fontsize=7, loc="upper left")
        for ax in col:
            ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("CV [-]")
    axes[1][0].set_ylabel("CV [-]")
    axes[2][0].set_ylabel("mean coating per parcel [%s]" % unit)
    axes[3][0].set_ylabel("standard deviation [%s]" % unit)
    save(fig, folder, "compare_side_by_side.png")


def comparison_report(folder):
    with open(os.path.join(folder, "comparison.json")) as fh:
        c = json.load(fh)
    reports = []
    for run in c["runs"]:
        with open(os.path.join(folder, run["report"])) as fh:
            reports.append((run, json.load(fh)))
    allmean = np.concatenate([num(r["snapshots"]["mean"]) for _, r in reports])
    f, unit = mass_unit(c, allmean)
    plot_side_by_side(reports, f, unit, folder)

    fig, ax = plt.subplots(figsize=(6, 4))
    for run, r in reports:
        s = r["snapshots"]
        style = "-" if run["well_mixed"] else "--"
        ax.plot(num(s["mean"]) * f, num(s["cv"]), style, marker=".", ms=3,
                label="%s (%s)" % (run.get("legend", run["label"]), "well mixed" if run["well_mixed"] else "poorly mixed"))
    ax.set_xlabel("mean coating mass per parcel [%s]" % unit)
    ax.set_ylabel("CV [-]")
    ax.set_title("CV against mean coated mass (paper Fig. 8)", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, folder, "compare_cv_mean.png")

    fig, axes = plt.subplots(1, 2, figsize=(11, 3.6))
    for run, r in reports:
        s = r["snapshots"]
        t = num(s["time"])
        axes[0].plot(t, num(s["mean"]) * f, label=run.get("legend", run["label"]))
        axes[1].plot(t, num(s["cv"]), label=run.get("legend", run["label"]))
    axes[0].set_ylabel("mean coating mass per parcel [%s]" % unit)
    axes[1].set_ylabel("CV [-]")
    for ax in axes:
        ax.set_xlabel("time [s]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    save(fig, folder, "compare_statistics_time.png")

    fig, axes = plt.subplots(1, len(reports), figsize=(3.4 * len(reports), 3.2), squeeze=False)
    for ax, (run, r) in zip(axes[0], reports):
        if not r["histograms"]:
            continue
        h = r["histograms"][-1]
        edges = num(h["edges"]) * f
        ax.bar(edges[:-1], h["counts"], width=np.diff(edges), align="edge", color="#7fa7d9", edgecolor="#2c5d9b",
               lw=0.5)
        ax.set_title("%s, t = %.3g s\nnever coated %.1f %%" % (run.get("legend", run["label"]), h["time"],
                                                             100 * h["uncoated_share"]),
                     fontsize=8)
        ax.set_xlabel("coating mass [%s]" % unit)
        ax.set_ylabel("parcels")
    save(fig, folder, "compare_histograms.png")


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    folder = argv[1]
    if os.path.exists(os.path.join(folder, "comparison.json")):
        comparison_report(folder)
    elif os.path.exists(os.path.join(folder, "report.json")):
        run_report(folder)
    else:
        print("plot_report.py: %s holds neither report.json nor comparison.json; run `cosim report` first"
              % folder, file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
