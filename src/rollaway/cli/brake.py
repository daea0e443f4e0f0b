"""``rollaway brake``: time series of one drum of the paper's model."""
from __future__ import annotations

from typing import Optional

import numpy as np
import typer

from rollaway.cli import options as opt
from rollaway.cli.output import FORMATS, write_table
from rollaway.errors import UserError, check_choice
from rollaway.hold import validate_hand_force
from rollaway.physics.drum import DIRECTIONS


def load_cli_model(params, overrides=()):
    """The --params model (set name, parameter or model file) with CLI overrides ``(key, value, flag)``."""
    from rollaway.model.drum_model import load_model
    model = load_model(params)
    p = model.params.with_overrides(list(overrides))
    return model if p is model.params else model.with_params(p)


def time_grid_s(t_end_s: float, dt_s: float, flag: str = "--t-end-s") -> np.ndarray:
    """Print times 0, dt, … and t_end itself where the steps do not land on it; *flag* names the option that gave
    t_end in an error."""
    if not np.isfinite(t_end_s) or t_end_s < 0:
        raise UserError(f"{flag} {t_end_s:g} must be ≥ 0 seconds, e.g. 3600 for one hour")
    if not np.isfinite(dt_s) or dt_s <= 0:
        raise UserError(f"--dt-s {dt_s:g} must be > 0 seconds, e.g. 600")
    rows = np.floor(t_end_s / dt_s + 1e-9)
    n = int(rows) if np.isfinite(rows) else 10_000_001
    if n > 10_000_000:
        raise UserError(f"{flag}/--dt-s gives {n} rows; use a larger --dt-s")
    t = np.arange(n + 1) * dt_s
    return t if t_end_s - t[-1] <= 1e-9 * max(t_end_s, 1.0) else np.append(t, t_end_s)


def brake(
    hand_force_N: float = typer.Option(..., "--hand-force-N", help="force on the hand lever [N], e.g. 250"),
    direction: str = opt.DIRECTION,
    t_end_s: float = typer.Option(3600.0, "--t-end-s", help="end of the series [s]"),
    dt_s: float = opt.DT_S,
    mu: Optional[float] = opt.MU_DRUM,
    gap_mm: Optional[float] = typer.Option(None, "--gap-mm", help="installation gap [mm]; > 0 selects eq. 16b"),
    t0_C: Optional[float] = opt.T0_C,
    params: Optional[str] = opt.PARAMS,
    fmt: str = opt.FORMAT,
) -> None:
    """Print the drum temperature, normal force and torque of ONE drum over time (paper eqs. 10, 16, 17b, 24).

    --params may be a model file: its effects are included.
    """
    check_choice(fmt, FORMATS, "format")
    check_choice(direction, DIRECTIONS, "direction")
    validate_hand_force(hand_force_N)
    model = load_cli_model(params, [
        ("mu_drum", mu, "--mu"),
        ("gap_m", None if gap_mm is None else gap_mm / 1000.0, "--gap-mm (in m)"),
        ("initial_drum_temp_C", t0_C, "--t0-C")])
    p = model.params
    t = time_grid_s(t_end_s, dt_s)
    series = model.evaluate(t, hand_force_N, direction)
    if bool(np.any(series.self_locked)):
        raise UserError(f"the shoe self-locks facing {direction} with μ_d = {p.mu_drum:g} "
                        f"(l_f − μ_d·l_fr ≤ 0, eqs. 18–21): the 1D model has no finite torque; lower --mu")
    write_table(series.columns(), fmt)


def register(app: typer.Typer) -> None:
    app.command("brake")(brake)
