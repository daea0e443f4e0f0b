"""``rollaway simulate``: run one scenario in MuJoCo, print the outcome, optionally render it."""
from __future__ import annotations

import json
from pathlib import Path
from typing import Optional

import typer

from rollaway.cli.output import write_table
from rollaway.errors import check_choice, ensure_parent_dir

_LABELS = (
    ("outcome", "outcome", ""), ("status", "status", ""), ("rollaway_time_s", "roll-away time", "s"),
    ("analytic_time_to_slip_s", "analytic brake slip time (eqs. 10-23)", "s"),
    ("max_displacement_m", "max displacement along slope", "m"), ("creep_m", "creep while held", "m"),
    ("min_margin", "min brake margin (capacity/demand)", "-"),
    ("capacity_Nm_at_rollaway", "rear-axle capacity at roll-away", "N·m"),
    ("demand_Nm", "rear-axle demand T_req (eq. 23)", "N·m"),
    ("tyre_adhesion_margin", "analytic tyre adhesion margin", "-"), ("slip_ratio", "rear slip ratio after roll-away", "-"),
    ("drum_temp_C_end", "drum temperature at the end", "°C"), ("sim_time_s", "simulated time", "s"),
    ("integrated_time_s", "of which integrated by MuJoCo", "s"), ("wall_time_s", "wall time", "s"),
)


def _cell(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def simulate(
    scenario_file: Path = typer.Argument(..., help="scenario TOML file (see scenarios/*.toml)"),
    render: Optional[str] = typer.Option(None, "--render", help="write a video/picture: FILE.mp4, FILE.gif or FILE.png"),
    json_file: Optional[str] = typer.Option(None, "--json", help="also write the result as JSON to this file"),
    mode: str = typer.Option("fast", "--mode", help="fast (event-driven skip while at rest) | fixed (plain 1 ms stepping)"),
) -> None:
    """Simulate a parked car held by the drum brake in MuJoCo: held, brake_slip or tyre_skid.

    Exit code 3 when the simulation diverged (outcome `diverged`, reason printed): no verdict.
    """
    from rollaway.scenario import load_scenario
    from rollaway.sim import simulate as run_sim
    from rollaway.sim.render import check_render_path
    from rollaway.sim.run import EXIT_DIVERGED, MODES

    check_choice(mode, MODES, "--mode")
    if render is not None:
        check_render_path(render)
    if json_file is not None:
        ensure_parent_dir(json_file, "--json")
    scenario = load_scenario(scenario_file)
    result = run_sim(scenario, render=render, mode=mode)
    d = result.to_dict()
    typer.echo(f"{scenario.name}: {scenario.description}" if scenario.description else scenario.name)
    write_table({"quantity": [lab for _, lab, _ in _LABELS], "value": [_cell(d[k]) for k, _, _ in _LABELS],
                 "unit": [u for _, _, u in _LABELS]}, "table")
    if render is not None:
        typer.echo(f"wrote {render}")
    if json_file is not None:
        payload = {**d, "scenario_file": str(scenario_file), "grade_pct": scenario.grade_pct,
                   "direction": scenario.direction, "occupants": scenario.occupants,
                   "hand_force_N": scenario.hand_force_N, "duration_s": scenario.duration_s}
        Path(json_file).write_text(json.dumps(payload, indent=1) + "\n", encoding="utf-8")
        typer.echo(f"wrote {json_file}")
    if result.outcome == "diverged":
        typer.echo(f"{scenario_file}: simulation diverged, no verdict: {result.diverged_reason}", err=True)
        raise typer.Exit(EXIT_DIVERGED)


def register(app: typer.Typer) -> None:
    app.command("simulate")(simulate)
