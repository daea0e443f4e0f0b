"""``rollaway hold``: the analytic hold check of one case over time."""
from __future__ import annotations

from typing import Optional

import numpy as np
import typer

from rollaway.cli.brake import time_grid_s
from rollaway.cli import options as opt
from rollaway.cli.output import FORMATS, write_table
from rollaway.errors import UserError, check_choice
from rollaway.hold import (analytic_verdict, effective_slope, hold_margin, minimum_hand_force_N, required_torque,
                           validate_grade, validate_hand_force, validate_occupants)
from rollaway.brake import drum_brake
from rollaway.parameters import load_parameters
from rollaway.physics.drum import DIRECTIONS
from rollaway.scenario import MAX_DURATION_S


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
    fmt: str = opt.FORMAT,
) -> int:
    """Analytic hold check of one parked car: margin over time, slip time, tyre margin, least hand force.

    Exit 0 if it holds for the whole duration, 1 if it rolls away.
    """
    check_choice(fmt, FORMATS, "format")
    check_choice(direction, DIRECTIONS, "direction")
    validate_grade(grade_pct)
    validate_hand_force(hand_force_N)
    validate_occupants(occupants)
    p = load_parameters(params).with_overrides([
        ("mu_drum", mu, "--mu"), ("initial_drum_temp_C", t0_C, "--t0-C"), ("tyre_road_mu", tyre_mu, "--tyre-mu")])
    if not (np.isfinite(duration_s) and 0 < duration_s <= MAX_DURATION_S):
        raise UserError(f"--duration-s {duration_s:g} must be in (0, {MAX_DURATION_S:.0f}] seconds, e.g. 3600")
    t = time_grid_s(duration_s, dt_s, "--duration-s")
    margin = hold_margin(p, t, hand_force_N, grade_pct, direction, occupants)
    s = drum_brake(p, time_s=t, hand_force_N=hand_force_N, direction=effective_slope(grade_pct, direction)[1])
    t_req = float(required_torque(p, grade_pct, occupants))
    write_table({"time_s": t, "drum_temp_C": s.drum_temp_C, "axle_torque_Nm": 2 * s.torque_Nm,
                 "required_torque_Nm": np.full_like(t, t_req), "hold_margin": margin}, fmt)
    v = analytic_verdict(p, hand_force_N=hand_force_N, grade_pct=grade_pct, direction=direction,
                         occupants=occupants, duration_s=duration_s)
    fmin = float(minimum_hand_force_N(p, grade_pct, direction, occupants, duration_s))
    if fmt == "table":
        slip = "never within the duration" if np.isnan(v.time_to_slip_s) else f"{v.time_to_slip_s:.0f} s"
        typer.echo(f"brake margin min {v.brake_margin_min:.3f}; brake slips: {slip}; tyre adhesion margin "
                   f"{v.tyre_margin:.3f}; least hand force holding {duration_s:g} s: {fmin:.1f} N")
        typer.echo(f"verdict: {'HOLDS' if v.holds else 'ROLLS AWAY'} ({v.reason})")
    return 0 if v.holds else 1


def register(app: typer.Typer) -> None:
    app.command("hold")(hold)
