"""Analogues of the paper's Figures 9–14 (Ishak et al. 2018), computed with the baseline model.

Each function draws one figure from the vectorised model and returns the path written.
Per-drum torque is T_gen (eq. 17b); comparisons with the demand T_req (eq. 23) use the
axle torque 2·T_gen (two rear drums behind one equaliser, docs/model.md, "Model chain" item 7).
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rollaway.model.brake import drum_brake, drum_temperature  # noqa: E402
from rollaway.hold import required_torque  # noqa: E402
from rollaway.model.parameters import BrakeParameters  # noqa: E402

HAND_FORCES_N = (200.0, 250.0, 300.0, 340.0, 400.0)
TIME_S = np.linspace(0.0, 3600.0, 361)
FMVSS_GRADE_PCT = 20.0          # 11.31°, the paper's Fig. 12
DIRECTIONS = ("downhill", "uphill")


def _save(fig, out_dir: Path, name: str) -> Path:
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / name
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _caption(fig, p: BrakeParameters, extra: str = "", mu: bool = True) -> None:
    """Footer naming the parameter set; *mu* False on figures that sweep μ_d themselves."""
    mu_text = f" · μ_d={p.mu_drum:g}" if mu else ""
    fig.text(0.01, 0.005, f"rollaway · parameter set '{p.name}'{mu_text} · T_0={p.initial_drum_temp_C:g} °C"
             f" · τ={p.cooling_time_constant_s:.0f} s {extra}", fontsize=8, color="0.4")


def fig09_temperature(p: BrakeParameters, out_dir: Path) -> Path:
    """Fig. 9: drum temperature against cooling time, eq. (10) (same for every hand force and direction)."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    temp = drum_temperature(p, TIME_S)
    ax.plot(TIME_S, temp, lw=1.8, label="drum, every hand force (eq. 10 does not depend on F_hb)")
    ax.axvline(500, color="0.6", ls=":", lw=1)
    ax.text(510, temp.max() * 0.95, "fast drop before ~500 s", fontsize=8, color="0.3")
    ax.axhline(p.ambient_temp_C, color="0.5", ls="--", lw=1, label=f"ambient {p.ambient_temp_C:g} °C")
    ax.set(xlabel="time since the lever was applied [s]", ylabel="drum temperature [°C]",
           title="Fig. 9 analogue: drum cooling, eq. (10)", xlim=(0, 3600))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _caption(fig, p)
    return _save(fig, out_dir, "fig09_temperature.png")


def _torque_vs_time(p: BrakeParameters, out_dir: Path, direction: str, number: str) -> Path:
    fig, ax = plt.subplots(figsize=(7, 4.5))
    f = np.array(HAND_FORCES_N)[:, None]
    s = drum_brake(p, time_s=TIME_S, hand_force_N=f, direction=direction)
    for i, fh in enumerate(HAND_FORCES_N):
        ax.plot(TIME_S, s.torque_Nm[i], lw=1.6, label=f"F_hb = {fh:g} N")
    # one y scale for Figs 10 and 11 (the larger, downhill torque), so the two directions compare at a glance
    top = max(float(np.nanmax(drum_brake(p, time_s=TIME_S, hand_force_N=f, direction=d).torque_Nm))
              for d in ("downhill", "uphill"))
    ax.set(xlabel="time since the lever was applied [s]", ylabel="brake torque of one drum T_gen [N·m]",
           title=f"Fig. {number} analogue: torque per drum, vehicle facing {direction}", xlim=(0, 3600),
           ylim=(0, top * 1.05))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    _caption(fig, p, "· eqs. (10), (16a), (17b), (18)–(21), (24)")
    return _save(fig, out_dir, f"fig{number}_torque_{direction}.png")


def fig10_torque_downhill(p, out_dir):
    """Fig. 10: torque against time for several hand forces, facing downhill."""
    return _torque_vs_time(p, out_dir, "downhill", "10")


def fig11_torque_uphill(p, out_dir):
    """Fig. 11: torque against time for several hand forces, facing uphill."""
    return _torque_vs_time(p, out_dir, "uphill", "11")


def fig12_generated_vs_required(p: BrakeParameters, out_dir: Path, hand_force_N: float = 400.0) -> Path:
    """Fig. 12: generated axle torque at 400 N against the torque required on 11.3° (20 %)."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    t_req = float(required_torque(p, FMVSS_GRADE_PCT, 1))
    for ax, d in zip(axes, DIRECTIONS):
        s = drum_brake(p, time_s=TIME_S, hand_force_N=hand_force_N, direction=d)
        ax.plot(TIME_S, 2 * s.torque_Nm, lw=2, label=f"generated 2·T_gen, F_hb = {hand_force_N:g} N")
        ax.axhline(t_req, color="C3", lw=2, ls="--", label=f"required T_req, 11.3° (20 %): {t_req:.0f} N·m")
        ax.fill_between(TIME_S, t_req, 2 * s.torque_Nm, where=2 * s.torque_Nm >= t_req, color="C2", alpha=0.12)
        ax.set(title=f"facing {d}", xlabel="time [s]", xlim=(0, 3600), ylim=(0, None))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
    axes[0].set_ylabel("rear-axle torque [N·m]")
    fig.suptitle("Fig. 12 analogue: FMVSS 135 check, driver only (1320 kg)")
    _caption(fig, p)
    return _save(fig, out_dir, "fig12_generated_vs_required.png")


def fig13_friction_sweep(p: BrakeParameters, out_dir: Path, hand_force_N: float = 400.0) -> Path:
    """Fig. 13: generated torque for friction coefficients 0.1–0.6 against the 20 % demand."""
    mus = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    t_req = float(required_torque(p, FMVSS_GRADE_PCT, 1))
    for ax, d in zip(axes, DIRECTIONS):
        s = drum_brake(p, time_s=TIME_S, hand_force_N=hand_force_N, direction=d, mu_drum=mus[:, None])
        for i, mu in enumerate(mus):
            holds = bool(np.all(2 * s.torque_Nm[i] >= t_req))
            ax.plot(TIME_S, 2 * s.torque_Nm[i], lw=1.6, ls="-" if holds else ":",
                    label=f"μ_d = {mu:.1f} ({'holds' if holds else 'rolls away'})")
        ax.axhline(t_req, color="k", lw=2, ls="--", label=f"T_req 20 %: {t_req:.0f} N·m")
        ax.set(title=f"facing {d}, F_hb = {hand_force_N:g} N", xlabel="time [s]", xlim=(0, 3600), ylim=(0, None))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    axes[0].set_ylabel("rear-axle torque 2·T_gen [N·m]")
    fig.suptitle("Fig. 13 analogue: drum/lining friction coefficient (paper: holds above μ ≈ 0.2)")
    _caption(fig, p, mu=False)
    return _save(fig, out_dir, "fig13_friction_sweep.png")


def fig14_occupants(p: BrakeParameters, out_dir: Path, hand_force_N: float = 400.0) -> Path:
    """Fig. 14: generated torque against the demand of 1–5 occupants on 20 %."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    occ = np.arange(1, 6)
    t_req = required_torque(p, FMVSS_GRADE_PCT, occ)
    for ax, d in zip(axes, DIRECTIONS):
        s = drum_brake(p, time_s=TIME_S, hand_force_N=hand_force_N, direction=d)
        ax.plot(TIME_S, 2 * s.torque_Nm, lw=2.2, color="C0", label=f"generated 2·T_gen, F_hb = {hand_force_N:g} N")
        for n, tr in zip(occ, t_req):
            m = p.vehicle_mass_kg + n * p.occupant_mass_kg
            ax.axhline(tr, lw=1.2, ls="--", color=plt.cm.Reds(0.35 + 0.13 * n), label=f"T_req, {n} occupant{'' if n == 1 else 's'}, {m:.0f} kg")
        ax.set(title=f"facing {d}", xlabel="time [s]", xlim=(0, 3600), ylim=(0, None))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("rear-axle torque [N·m]")
    fig.suptitle("Fig. 14 analogue: vehicle weight with 1–5 occupants, 20 % grade")
    _caption(fig, p)
    return _save(fig, out_dir, "fig14_occupants.png")


FIGURES = (fig09_temperature, fig10_torque_downhill, fig11_torque_uphill, fig12_generated_vs_required,
           fig13_friction_sweep, fig14_occupants)


def paper_figures(p: BrakeParameters, out_dir: Path) -> list[Path]:
    """Write all six figures to *out_dir*; return their paths."""
    return [f(p, Path(out_dir)) for f in FIGURES]
