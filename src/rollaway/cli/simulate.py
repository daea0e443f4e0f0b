"""``rollaway simulate``: run one scenario in MuJoCo, print the outcome, optionally render it (:func:`rollaway.simulate`)."""
from __future__ import annotations

import json
from pathlib import Path
from typing import Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.output import REPORT_FORMATS, echo_json, write_table
from rollaway.errors import UserError, check_choice, ensure_parent_dir

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
VERDICTS = {"held": "HOLDS", "brake_slip": "ROLLS AWAY (the drum brake slips)",
            "tyre_skid": "ROLLS AWAY (the rear tyres skid)"}


def _cell(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def parse_size(text: str | None) -> tuple[int, int] | None:
    """``"640x480"`` → (640, 480); UserError naming the option otherwise."""
    if text is None:
        return None
    parts = text.lower().replace("×", "x").split("x")
    try:
        w, h = (int(p) for p in parts)
    except ValueError:
        raise UserError(f"--size {text!r}: give WIDTHxHEIGHT in pixels, e.g. --size 640x480") from None
    if not (16 <= w <= 3840 and 16 <= h <= 2160):
        raise UserError(f"--size {text}: each side must be 16–3840 px wide and 16–2160 px high, e.g. 640x480")
    return w, h


def payload(scenario, result, scenario_file) -> dict:
    """The result as a JSON object with the decision first."""
    d = result.to_dict()
    return {"verdict": VERDICTS.get(d["outcome"], d["outcome"]), "holds": d["outcome"] == "held", **d,
            "scenario_file": str(scenario_file), "grade_pct": scenario.grade_pct, "direction": scenario.direction,
            "occupants": scenario.occupants, "hand_force_N": scenario.hand_force_N,
            "duration_s": scenario.duration_s}


def simulate(
    scenario_file: Path = typer.Argument(..., metavar="SCENARIO_TOML", help="scenario file (see scenarios/*.toml)"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help="text | json (the result on stdout)"),
    render: Optional[str] = typer.Option(None, "--render", metavar="FILE",
                                         help="write a video or picture: FILE.mp4, FILE.gif or FILE.png"),
    fps: Optional[float] = typer.Option(None, "--fps", metavar="N", help="video frame rate (default: 25 mp4, 10 gif)"),
    size: Optional[str] = typer.Option(None, "--size", metavar="WxH",
                                       help="picture size in pixels, e.g. 640x480 (default: 640x360 mp4, "
                                            "480x270 gif, 960x540 png)"),
    after_s: Optional[float] = typer.Option(None, "--after-s", metavar="SECONDS",
                                            help="the video goes on this long after a roll-away (or until 15 m of "
                                                 "travel; default 10)"),
    multisample: Optional[int] = typer.Option(None, "--multisample", metavar="N",
                                              help="anti-aliasing samples per pixel (0: off, the default, fast under "
                                                   "software GL; 4: smooth)"),
    json_file: Optional[str] = typer.Option(None, "--json", metavar="FILE", help="also write the result as JSON here"),
    mode: str = typer.Option("fast", "--mode", metavar="MODE",
                             help="fast (event-driven skip while at rest) | fixed (plain 1 ms stepping)"),
    params: Optional[str] = opt.params_option("drum model for this run: a set name, parameter file or model file "
                                              "(.toml; replaces the scenario's 'params')"),
    uncertainty: Optional[int] = opt.uncertainty_option("draw N parameter vectors from the model's covariance and "
                                                   "simulate the --percentile draw"),
    percentile: Optional[float] = typer.Option(None, "--percentile", metavar="Q",
                                               help="with --uncertainty: which draw to simulate, by its least margin "
                                                    "(default 5 = a pessimistic draw)"),
) -> int:
    """Simulate a parked car held by the drum brake in MuJoCo: held, brake_slip or tyre_skid.

    The verdict is in the output (--format json: "verdict" and "holds"); the exit code is 0 for
    any finished simulation (use 'rollaway check SCENARIO_TOML' for a pass/fail exit code).
    The brake torque comes from the scenario's drum model, effects included (--params
    FILE.toml from 'rollaway fit --save-model').  Exit code 3 when the simulation diverged
    (outcome `diverged`, reason printed): no verdict.
    """
    from rollaway.api import build_scenario
    from rollaway.api import simulate as run_sim
    from rollaway.cli.inputs import expect_scenario
    from rollaway.sim.render import check_render_path
    from rollaway.sim.run import EXIT_DIVERGED, MODES

    check_choice(fmt, REPORT_FORMATS, "--format")
    check_choice(mode, MODES, "--mode")
    given = {"--fps": fps, "--size": size, "--after-s": after_s, "--multisample": multisample}
    render_opts = {"size": parse_size(size), "fps": fps, "after_s": 10.0 if after_s is None else after_s,
                   "multisample": multisample or 0}
    from rollaway.sim.render import check_render_options
    check_render_options(**render_opts)
    if render is None:
        opt.only_with("--render FILE (the video or picture)", **given)
    if uncertainty is None:
        opt.only_with("--uncertainty N (draws from the model file's covariance)", **{"--percentile": percentile})
    percentile = 5.0 if percentile is None else percentile
    if render is not None:
        check_render_path(render)
    if json_file is not None:
        ensure_parent_dir(json_file, "--json")
    expect_scenario(scenario_file, "simulate")
    scenario = build_scenario(scenario_file, model=params)
    if uncertainty is not None:
        scenario = _percentile_draw(scenario, uncertainty, percentile)
    result = run_sim(scenario, render=render, mode=mode, render_options=render_opts)
    data = payload(scenario, result, scenario_file)
    if fmt == "json":
        echo_json(data)
    else:
        typer.echo(f"{scenario.name}: {scenario.description}" if scenario.description else scenario.name)
        d = result.to_dict()
        write_table({"quantity": [lab for _, lab, _ in _LABELS], "value": [_cell(d[k]) for k, _, _ in _LABELS],
                     "unit": [u for _, _, u in _LABELS]}, "table")
        typer.echo(f"verdict: {data['verdict']}")
    say = (lambda m: typer.echo(m, err=True)) if fmt == "json" else typer.echo
    if render is not None:
        say(f"wrote {render}")
    if json_file is not None:
        Path(json_file).write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
        say(f"wrote {json_file}")
    if result.outcome == "diverged":
        typer.echo(f"{scenario_file}: simulation diverged, no verdict: {result.diverged_reason}", err=True)
        raise typer.Exit(EXIT_DIVERGED)
    return 0


def _percentile_draw(scenario, draws: int, percentile: float):
    """The scenario with the model at the draw whose least margin is at *percentile* (printed)."""
    import dataclasses

    from rollaway.uncertainty.draws import rollaway_risk
    risk = rollaway_risk(scenario.model, hand_force_N=scenario.hand_force_N, grade_pct=scenario.grade_pct,
                         direction=scenario.direction, occupants=scenario.occupants, duration_s=scenario.duration_s,
                         draws=draws)
    draw = risk.draw_at_percentile(percentile)
    model = scenario.model.with_draw(draw)
    typer.echo(f"uncertainty: roll-away probability {risk.rollaway_probability:.3f} over {draws} draws; simulating "
               f"the p{percentile:g} draw: " + ", ".join(f"{k} = {v:.5g}" for k, v in draw.items()))
    return dataclasses.replace(scenario, params=model.params, model=model)


def register(app: typer.Typer) -> None:
    app.command("simulate")(simulate)
