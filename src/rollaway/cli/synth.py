"""``rollaway synth``: bench-like measurements from the baseline plus chosen (hidden) effects."""
from __future__ import annotations

import sys
from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.identify_common import load_plugins, parse_effects
from rollaway.errors import ensure_parent_dir


def synth(
    effect: List[str] = typer.Option([], "--effect", help="effect to hide: NAME or NAME=param=value,... "
                                                          "(repeatable; unset parameters take typical values)"),
    out: Optional[str] = typer.Option(None, "--out", help="CSV file to write (default: stdout)"),
    seed: int = typer.Option(0, "--seed", min=0, help="random seed (same seed, same file)"),
    noise_torque_Nm: float = typer.Option(8.0, "--noise-torque-Nm", help="torque noise σ [N·m]"),
    noise_temp_C: float = typer.Option(1.5, "--noise-temp-C", help="drum-temperature noise σ [°C]"),
    mu: Optional[float] = typer.Option(None, "--mu", help="true μ_d (default: the set's, 0.4)"),
    h: Optional[float] = typer.Option(None, "--h", help="true h [W/(m² K)] (default: the set's, 40)"),
    hand_force_N: List[float] = typer.Option([], "--hand-force-N", help="hand forces (default 200 245 290 340)"),
    t0_C: float = typer.Option(200.0, "--t0-C", help="mean drum temperature at lever application [°C]"),
    dt_s: float = typer.Option(300.0, "--dt-s", help="sampling interval [s]"),
    duration_s: float = typer.Option(3600.0, "--duration-s", help="length of each test [s]"),
    params: Optional[str] = opt.params_option(),
    effect_file: List[str] = typer.Option([], "--effect-file", help="Python file defining Effect subclasses"),
) -> None:
    """Write synthetic bench data (both directions, a sample every 5 min for an hour, Gaussian noise)."""
    from rollaway.identify.synth import DEFAULT_HAND_FORCES_N
    from rollaway.identify.synth import synth as run

    if not effect:
        opt.only_with("--effect NAME (synth hides only the effects it is given)", **{"--effect-file": effect_file})
    _check_size(len(hand_force_N) or 4, duration_s, dt_s, t0_C)
    load_plugins(effect_file)
    data = run(parse_effects(effect), params=params, seed=seed, noise_torque_Nm=noise_torque_Nm,
               noise_temp_C=noise_temp_C, mu_drum=mu, heat_transfer_W_m2K=h,
               hand_forces_N=tuple(hand_force_N) or DEFAULT_HAND_FORCES_N, initial_temp_C=t0_C, dt_s=dt_s,
               duration_s=duration_s)
    if out:
        ensure_parent_dir(out, "--out")
        data.to_csv(out)
        typer.echo(f"wrote {len(data)} rows, {data.n_tests} tests to {out}", err=True)
    else:
        data.to_frame().to_csv(sys.stdout, index=False, float_format="%.6g")


MAX_ROWS = 10_000_000       # a synthetic campaign larger than this is a typo in --dt-s or --duration-s


def _check_size(forces: int, duration_s: float, dt_s: float, t0_C: float) -> None:
    """UserError for a campaign too large to write, or a drum temperature no bench log can have."""
    from rollaway.bench.dataset import LIMITS
    from rollaway.errors import UserError
    lo, hi, _ = LIMITS["drum_temp_C"]
    if not lo <= t0_C <= hi:
        raise UserError(f"--t0-C {t0_C:g} is outside [{lo:g}, {hi:g}] °C; give the drum temperature at lever "
                        f"application, e.g. 200")
    if dt_s > 0 and forces * 2 * (duration_s / dt_s + 1) > MAX_ROWS:
        raise UserError(f"--duration-s {duration_s:g} with --dt-s {dt_s:g} gives about "
                        f"{forces * 2 * (duration_s / dt_s + 1):.3g} rows (> {MAX_ROWS:,}); use a larger --dt-s")


def register(app: typer.Typer) -> None:
    app.command("synth")(synth)
