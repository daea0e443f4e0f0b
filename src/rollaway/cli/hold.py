"""``rollaway hold``: the analytic hold check of one case over time, for any drum model (:func:`rollaway.hold`)."""
from __future__ import annotations

import json
import sys
from typing import Optional

import numpy as np
import typer

from rollaway.cli import options as opt
from rollaway.cli.brake import load_cli_model, time_grid_s
from rollaway.cli.output import FORMATS, write_table
from rollaway.errors import UserError, check_choice
from rollaway.hold import (effective_slope, hold_margin, required_torque, validate_grade, validate_hand_force,
                           validate_occupants)
from rollaway.jsonsafe import to_jsonable
from rollaway.physics.drum import DIRECTIONS
from rollaway.hold.scenario import MAX_DURATION_S


def hold(
    grade_pct: float = typer.Option(..., "--grade-pct", help="road grade [%], e.g. 20 (negative flips the facing)"),
    hand_force_N: float = typer.Option(..., "--hand-force-N", help="force on the hand lever [N]"),
    direction: str = opt.DIRECTION,
    occupants: int = typer.Option(1, "--occupants", help="number of 70 kg occupants, 0–5"),
    duration_s: float = typer.Option(3600.0, "--duration-s", help="how long the car must stay parked [s]"),
    dt_s: float = opt.DT_S,
    mu: Optional[float] = opt.MU_DRUM,
    t0_C: Optional[float] = opt.T0_C,
    tyre_mu: Optional[float] = typer.Option(None, "--tyre-mu", help="tyre–road friction μ_r (default: the set's)"),
    params: Optional[str] = opt.PARAMS,
    uncertainty: Optional[int] = opt.UNCERTAINTY,
    seed: Optional[int] = opt.SEED,
    fmt: str = opt.FORMAT,
) -> int:
    """Analytic hold check of one parked car: margin over time, slip time, tyre margin, least hand force.

    --params takes a set name, a parameter file or a model file (e.g. one saved by
    'rollaway fit --save-model'): its effects are included.  --uncertainty N draws N
    parameter vectors from the model's covariance and reports the roll-away probability.
    Exit 0 if it holds for the whole duration, 1 if it rolls away, 2 on bad input or a
    self-locking shoe (outside the model).
    """
    check_choice(fmt, FORMATS, "format")
    if uncertainty is None:
        opt.only_with("--uncertainty N (draws from the model file's covariance)", **{"--seed": seed})
    check_choice(direction, DIRECTIONS, "direction")
    validate_grade(grade_pct)
    validate_hand_force(hand_force_N)
    validate_occupants(occupants)
    if not (np.isfinite(duration_s) and 0 < duration_s <= MAX_DURATION_S):
        raise UserError(f"--duration-s {duration_s:g} must be in (0, {MAX_DURATION_S:.0f}] seconds, e.g. 3600")
    model = load_cli_model(params, [("mu_drum", mu, "--mu"), ("initial_drum_temp_C", t0_C, "--t0-C"),
                                    ("tyre_road_mu", tyre_mu, "--tyre-mu")])
    t = time_grid_s(duration_s, dt_s, "--duration-s")
    from rollaway.api import hold as run
    v = run(model, hand_force_N=hand_force_N, grade_pct=grade_pct, direction=direction, occupants=occupants,
            duration_s=duration_s, initial_drum_temp_C=None, uncertainty=uncertainty, seed=0 if seed is None else seed)
    risk = v.risk
    if v.outcome == "self_locking":
        if fmt == "json":
            typer.echo(json.dumps(to_jsonable({**v.as_dict(), "model": model.name}), indent=1))
        raise UserError(f"{v.reason}; lower --mu or use another parameter set")
    s = model.evaluate(t, hand_force_N, effective_slope(grade_pct, direction)[1])
    series = {"time_s": t, "drum_temp_C": s.drum_temp_C, "axle_torque_Nm": 2 * s.torque_Nm,
              "required_torque_Nm": np.full_like(t, float(required_torque(model, grade_pct, occupants))),
              "hold_margin": hold_margin(model, t, hand_force_N, grade_pct, direction, occupants)}
    summary = {**v.as_dict(), "model": model.name, "effects": [e.name for e, _ in model.active()],
               "duration_s": duration_s, **({"uncertainty": risk.as_dict()} if risk else {})}
    if fmt == "json":
        typer.echo(json.dumps(to_jsonable({**summary, "series": {k: list(x) for k, x in series.items()}}), indent=1))
    elif fmt == "csv":
        for k, x in summary.items():           # the decision first, as comment lines a CSV reader skips
            sys.stdout.write(f"# {k}: {json.dumps(to_jsonable(x))}\n")
        write_table(series, fmt)
    else:
        write_table(series, fmt)
        typer.echo(_summary_text(v, duration_s, model, risk))
    return 0 if v.holds else 1


def _summary_text(v, duration_s: float, model, risk) -> str:
    slip = "never within the duration" if np.isnan(v.time_to_slip_s) else f"{v.time_to_slip_s:.0f} s"
    if v.least_hand_force_N is not None:
        force = f"{v.least_hand_force_N:.1f} N"
    else:
        force = "none (the rear tyres slide whatever the brake does)" if v.tyre_margin < 1 else "none can hold"
    lines = [f"model: {model.name}",
             f"brake margin min {v.brake_margin_min:.3f}; brake slips: {slip}; tyre adhesion margin "
             f"{v.tyre_margin:.3f}; least hand force holding {duration_s:g} s: {force}"]
    if risk is not None:
        lm, ts = risk.brake_margin_percentiles, risk.slip_time_percentiles_s
        fmt_t = lambda x: "holds" if x is None else f"{x:.0f} s"  # noqa: E731
        lines.append(f"uncertainty ({risk.draws} predictive draws): roll-away probability "
                     f"{risk.rollaway_probability:.3f}; least brake margin p5/p50/p95 {lm['p5']:.3f}/{lm['p50']:.3f}/"
                     f"{lm['p95']:.3f}; slip time p5/p50/p95 {fmt_t(ts['p5'])}/{fmt_t(ts['p50'])}/{fmt_t(ts['p95'])}")
        lines.append(f"  {risk.band_words()}")
    beyond = f" — beyond the bench data: {'; '.join(risk.flags)}" if risk is not None and risk.flags else ""
    doubt = "" if risk is None else risk.not_sure(v.holds)      # the band gives the other answer ≥ 5 %
    lines.append(f"verdict: {'HOLDS' if v.holds else 'ROLLS AWAY'}" + ("" if v.holds else f" ({v.reason})")
                 + (f" at the calibrated values, {doubt}" if doubt else "") + beyond)
    return "\n".join(lines)


def register(app: typer.Typer) -> None:
    app.command("hold")(hold)
