"""Design chart: the least hand force that holds a parked car, against grade, for several drum models.

One line per model and facing: :func:`rollaway.hold.minimum_hand_force_N` over grades (closed
form for the paper's chain, numeric for a model with effects), so a calibrated model can be
compared with the paper model at a glance.  The regulation's 400 N and 20 % are marked.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rollaway.hold import minimum_hand_force_N, tyre_adhesion_margin

GRADES_PCT = np.linspace(1.0, 40.0, 79)
REGULATION_FORCE_N = 400.0      # FMVSS 135 / UN R13-H hand-control limit
REGULATION_GRADE_PCT = 20.0


def least_force_curves(models: dict, *, occupants: int, duration_s: float, initial_temp_C: float):
    """{(label, facing): least hand force [N] per grade (NaN where the tyres slide)}."""
    out = {}
    for label, model in models.items():
        for facing in ("downhill", "uphill"):
            f = minimum_hand_force_N(model, GRADES_PCT, facing, occupants, duration_s, initial_temp_C=initial_temp_C)
            tyre = tyre_adhesion_margin(model, GRADES_PCT, facing, occupants)
            out[(label, facing)] = np.where(tyre >= 1.0, f, np.nan)
    return out


BAND_GRADES_PCT = np.linspace(1.0, 40.0, 14)


def design_chart(models: dict, out: str | Path, *, occupants: int = 5, duration_s: float = 3600.0,
                 initial_temp_C: float = 200.0, uncertainty: int = 0) -> Path:
    """Draw the chart to *out* (PNG); *models* maps a label to a parameter set or drum model.
    *uncertainty*: draws for a shaded 5–95 % band of each calibrated model's least hand force."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    curves = least_force_curves(models, occupants=occupants, duration_s=duration_s, initial_temp_C=initial_temp_C)
    fig, ax = plt.subplots(figsize=(8, 5), dpi=110)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, label in enumerate(models):
        for facing, ls in (("downhill", "-"), ("uphill", "--")):
            ax.plot(GRADES_PCT, curves[(label, facing)], ls, color=colours[i % len(colours)], lw=2,
                    label=f"{label}, facing {facing}")
            model = models[label]
            if uncertainty and (getattr(model, "covariance", None) is not None or getattr(model, "predictive", None)):
                from rollaway.uncertainty.draws import least_force_band
                band = least_force_band(model, BAND_GRADES_PCT, facing, occupants, duration_s, initial_temp_C,
                                        draws=uncertainty)
                ax.fill_between(BAND_GRADES_PCT, band["p5"], band["p95"], color=colours[i % len(colours)],
                                alpha=0.18 if facing == "downhill" else 0.10, lw=0,
                                label=f"{label}, facing {facing}: 5–95 % band")
    ax.axhline(REGULATION_FORCE_N, color="0.3", lw=1)
    ax.text(GRADES_PCT[0], REGULATION_FORCE_N * 1.02, "400 N hand-control limit", fontsize=10, color="0.3")
    ax.axvline(REGULATION_GRADE_PCT, color="0.3", lw=1, ls=":")
    ax.text(REGULATION_GRADE_PCT + 0.4, 0.97, "20 % grade (FMVSS 135, UN R13-H)", fontsize=10, color="0.3",
            rotation=90, va="top", transform=ax.get_xaxis_transform())
    ax.set_xlabel("grade [%]", fontsize=11)
    ax.set_ylabel("least hand force that holds [N]", fontsize=11)
    ax.set_title(f"Least hand force holding {duration_s:g} s from T₀ = {initial_temp_C:g} °C, {occupants} "
                 f"occupant{'s' if occupants != 1 else ''} (lines end where the rear tyres slide)", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9)
    fig.subplots_adjust(left=0.1, right=0.97, top=0.92, bottom=0.11)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out)
    plt.close(fig)
    return out
