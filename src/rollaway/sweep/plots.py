"""Sweep plots: hold/roll-away maps and the minimum-hand-force design chart (PNG, Agg).

The maps draw the analytic margin min(brake, tyre) on a dense grid over the sweep's range
(contours; margin = 1 bold; hold shaded green, roll-away red), the paper's brake-only boundary
dashed, and the sweep's own points of that slice on top: simulated points with their MuJoCo
outcome, analytic-only points as small dots.  Axes not on the map are held at a reference
value: the base scenario's value when the sweep contains it, else the sweep's median value.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from rollaway.hold import MAX_OCCUPANTS, minimum_hand_force_N, tyre_adhesion_margin  # noqa: E402
from rollaway.sweep.analytic import analytic_pass  # noqa: E402
from rollaway.sweep.spec import AXES, SweepSpec  # noqa: E402

LEVELS = (0.5, 0.75, 1.5, 2.0, 3.0)    # thin contours, plus the band edges of the sweep
MARKERS = {"held": ("o", "tab:green", "simulated: held"), "brake_slip": ("X", "tab:red", "simulated: brake slip"),
           "tyre_skid": ("^", "tab:orange", "simulated: tyre skid")}
REG_HAND_FORCE_N = 400.0
REG_GRADE_PCT = 20.0
LABELS = {"grade_pct": "grade [%]", "occupants": "occupants (70 kg each)", "hand_force_N": "hand force [N]"}


def reference_values(table: pd.DataFrame, spec: SweepSpec) -> dict:
    """Value of each axis for the slice a map shows."""
    ref = {}
    for a in AXES:
        vals = pd.unique(table[a])
        base = getattr(spec.base, a)
        if base in set(vals):
            ref[a] = base
        elif a == "direction":
            ref[a] = vals[0]
        else:
            ref[a] = float(np.sort(vals)[len(vals) // 2])
    return ref


def _span(table, axis, default):
    vals = table[axis].to_numpy(float)
    vals = vals[np.isfinite(vals)]
    lo, hi = (float(vals.min()), float(vals.max())) if len(vals) else default
    if hi - lo < 1e-9:
        lo, hi = default
    return lo, hi


def _grade_axis(table) -> np.ndarray:
    lo, hi = _span(table, "grade_pct", (0.0, 40.0))
    return np.linspace(max(lo, -99.0), min(hi, 100.0), 161)


def _dense(spec, ref, x_axis, xs, y_axis, ys, direction) -> np.ndarray:
    """Analytic margins on the x × y grid for one direction: arrays (brake, combined) shaped (ny, nx)."""
    X, Y = np.meshgrid(xs, ys)
    df = pd.DataFrame({a: np.full(X.size, ref[a], dtype=object if a == "direction" else float) for a in AXES})
    df["direction"] = direction
    df[x_axis], df[y_axis] = X.ravel(), Y.ravel()
    res = analytic_pass(spec.base, df, spec.band)
    return (res["brake_margin_min"].to_numpy(float).reshape(X.shape),
            res["margin"].to_numpy(float).reshape(X.shape))


def _slice(table, ref, free, direction):
    """The rows of the map's slice, with only the columns a map draws (small even for 2e6 points)."""
    mask = (table["direction"] == direction).to_numpy(bool, copy=True)
    for a in AXES:
        if a not in free and a != "direction":
            mask &= np.isclose(table[a].to_numpy(float), float(ref[a]))
    cols = list(dict.fromkeys([*free, "simulated", "sim_outcome", "agree"]))
    return table.loc[mask, cols]


MAX_MARKERS = 4000   # markers drawn per kind and panel; more are evenly thinned (the contours show the rest)


def _thin(rows: pd.DataFrame) -> pd.DataFrame:
    return rows.iloc[::-(-len(rows) // MAX_MARKERS)] if len(rows) > MAX_MARKERS else rows


def _map(table, spec, y_axis, ys, path) -> Path:
    ref = reference_values(table, spec)
    xs = _grade_axis(table)
    directions = sorted(pd.unique(table["direction"]))
    fig, axes = plt.subplots(1, len(directions), figsize=(6.2 * len(directions), 5), squeeze=False, sharey=True)
    for ax, d in zip(axes[0], directions):
        brake, margin = _dense(spec, ref, "grade_pct", xs, y_axis, ys, d)
        m = np.clip(np.nan_to_num(margin, nan=0.0, posinf=10.0), 0, 10)
        ax.contourf(xs, ys, m, levels=[0, 1, 10], colors=["#f4b6b6", "#cdebc5"], alpha=0.8)
        cs = ax.contour(xs, ys, m, levels=sorted(set(LEVELS) | set(spec.band)), colors="0.35", linewidths=0.7)
        ax.clabel(cs, fmt="%.2g", fontsize=7)
        ax.contour(xs, ys, m, levels=[1.0], colors="k", linewidths=2.5)
        b = np.clip(np.nan_to_num(brake, nan=0.0, posinf=10.0), 0, 10)
        ax.contour(xs, ys, b, levels=[1.0], colors="navy", linewidths=1.2, linestyles="--")
        pts = _slice(table, ref, ("grade_pct", y_axis), d)
        plain = _thin(pts[~pts["simulated"]])
        ax.plot(plain["grade_pct"], plain[y_axis], ".", color="0.3", ms=3, label="analytic only")
        for outcome, (mk, col, lab) in MARKERS.items():
            s = pts[pts["simulated"] & (pts["sim_outcome"] == outcome)]
            if len(s):
                ax.scatter(s["grade_pct"], s[y_axis], marker=mk, c=col, s=40, edgecolors="k", linewidths=0.5,
                           label=lab, zorder=3)
        bad = _thin(pts[pts["agree"] == False])  # noqa: E712
        if len(bad):
            ax.scatter(bad["grade_pct"], bad[y_axis], marker="o", facecolors="none", edgecolors="magenta", s=110,
                       linewidths=1.3, label="paper's check disagrees", zorder=4)
        ax.plot([], [], "k-", lw=2.5, label="margin = 1 (brake and tyres)")
        ax.plot([], [], "--", color="navy", lw=1.2, label="paper's boundary (brake only)")
        ax.set_title(f"facing {d}")
        ax.set_xlabel(LABELS["grade_pct"])
        ax.grid(alpha=0.25)
    axes[0][0].set_ylabel(LABELS[y_axis])
    pad = 0.03 * (ys[-1] - ys[0] or 1.0)
    axes[0][0].set_ylim(ys[0] - pad, ys[-1] + pad)
    handles = {}
    for ax in axes[0]:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(handles.values(), handles.keys(), loc="lower center", ncol=4, fontsize=8, frameon=False)
    fixed = ", ".join(f"{a} = {ref[a]:g}" for a in AXES if a not in ("grade_pct", y_axis, "direction"))
    fig.suptitle(f"Hold (green) / roll-away (red) map: analytic margin contours — {fixed}", fontsize=10)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def design_chart(table, spec, path) -> Path:
    """Least hand force that holds for the duration, against grade, per direction and load."""
    ref = reference_values(table, spec)
    lo, hi = _span(table, "grade_pct", (0.0, 40.0))
    g = np.linspace(max(0.0, lo), max(min(hi, 100.0), 1.0), 241)
    loads = sorted({int(o) for o in pd.unique(table["occupants"]) if float(o).is_integer() and 0 <= o <= MAX_OCCUPANTS})
    loads = loads or [int(ref["occupants"])]
    p = spec.base.params
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for d, cmap, style in (("downhill", plt.cm.Blues, "-"), ("uphill", plt.cm.Reds, "--")):
        if d not in set(pd.unique(table["direction"])):
            continue
        for i, n in enumerate(loads):
            colour = cmap(0.45 + 0.55 * (i + 1) / len(loads))
            f = minimum_hand_force_N(p, g, d, n, ref["duration_s"], ref["mu_drum"], None, ref["initial_drum_temp_C"])
            tyre = tyre_adhesion_margin(p, g, d, n, ref["tyre_road_mu"])
            f = np.where(tyre >= 1.0, f, np.nan)
            ax.plot(g, f, color=colour, ls=style, lw=1.7, label=f"facing {d}, {n} occupant{'s' if n != 1 else ''}")
            skid = np.flatnonzero(tyre < 1.0)
            if len(skid) and skid[0] > 0:
                ax.plot(g[skid[0] - 1], f[skid[0] - 1], "x", color=colour, ms=9, mew=2)
    ax.axhline(REG_HAND_FORCE_N, color="k", lw=1.2)
    ax.text(g[0], REG_HAND_FORCE_N * 1.02, " 400 N hand-force limit (FMVSS 135, UN R13-H)", fontsize=8, va="bottom")
    ax.axvline(REG_GRADE_PCT, color="k", lw=0.8, ls=":")
    top = max(800.0, REG_HAND_FORCE_N * 1.6)
    ax.text(REG_GRADE_PCT, top * 0.97, f" {REG_GRADE_PCT:g} % test grade (FMVSS 135, UN R13-H)", fontsize=8,
            va="top", rotation=90, ha="right")
    if g[0] <= 0.0:
        ax.annotate("0 % grade: nothing to hold,\nno hand force needed", (0.0, 0.0), xytext=(g[-1] * 0.03, top * 0.12),
                    fontsize=8, arrowprops={"arrowstyle": "->", "color": "0.4"})
    ax.set_ylim(0, top)
    ax.set_xlim(g[0], g[-1])
    ax.set_xlabel(LABELS["grade_pct"])
    ax.set_ylabel("minimum hand force that holds [N]")
    ax.set_title(f"Design chart: least hand force holding for {ref['duration_s']:g} s "
                 f"(μ_d = {ref['mu_drum']:g}, T_0 = {ref['initial_drum_temp_C']:g} °C, μ_r = {ref['tyre_road_mu']:g});"
                 f"\n× = rear tyres skid beyond this grade (no hand force holds)", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def make_plots(table: pd.DataFrame, spec: SweepSpec, folder: str | Path) -> list[Path]:
    """Write the two maps and the design chart into *folder*; return their paths."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    ok = (table["error"] == "").to_numpy(bool)
    valid = table if ok.all() else table[ok]           # no copy of a large table that is all valid
    if valid.empty:
        return []
    lo, hi = _span(valid, "hand_force_N", (0.0, 600.0))
    forces = np.linspace(max(lo, 0.0), hi, 121)
    return [_map(valid, spec, "occupants", np.arange(MAX_OCCUPANTS + 1, dtype=float), folder / "map-grade-occupants.png"),
            _map(valid, spec, "hand_force_N", forces, folder / "map-grade-hand-force.png"),
            design_chart(valid, spec, folder / "design-chart.png")]
