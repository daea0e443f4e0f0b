"""``rollaway check``: regulation hold checks (analytic here; MuJoCo gate in :mod:`rollaway.compliance`)."""
from __future__ import annotations

from typing import List, Optional

import numpy as np
import typer

from rollaway.cli import options as opt

from rollaway.cli.output import FORMATS, write_table
from rollaway.errors import UserError, check_choice
from rollaway.hold import analytic_verdict
from rollaway.model import load_model
from rollaway.regulations import PRESETS, get_preset

DEFAULT_PRESETS = ("fmvss135", "unr13h")


def analytic_rows(preset_names, params, uncertainty: int | None = None) -> dict[str, list]:
    cols: dict[str, list] = {k: [] for k in (
        "preset", "direction", "grade_pct", "occupants", "hand_force_N", "duration_s", "min_brake_margin",
        "tyre_margin", "min_hand_force_N", "verdict", "reason")}
    if uncertainty is not None:
        cols["rollaway_probability"] = []
    for name in preset_names:
        pr = get_preset(name)
        for d in pr.directions:
            v = analytic_verdict(params, hand_force_N=pr.hand_force_N, grade_pct=pr.grade_pct, direction=d,
                                 occupants=pr.occupants, duration_s=pr.duration_s, initial_temp_C=pr.initial_temp_C)
            # no number where none holds: the tyres slide (or the shoe self-locks) whatever the hand force
            fmin = float("nan") if v.least_hand_force_N is None else v.least_hand_force_N
            for k, val in (("preset", name), ("direction", d), ("grade_pct", pr.grade_pct),
                           ("occupants", pr.occupants), ("hand_force_N", pr.hand_force_N),
                           ("duration_s", pr.duration_s), ("min_brake_margin", v.brake_margin_min),
                           ("tyre_margin", v.tyre_margin), ("min_hand_force_N", fmin),
                           ("verdict", "PASS" if v.holds else "FAIL"), ("reason", v.reason)):
                cols[k].append(val)
            if uncertainty is not None:
                from rollaway.uncertainty import rollaway_risk
                cols["rollaway_probability"].append(rollaway_risk(
                    params, hand_force_N=pr.hand_force_N, grade_pct=pr.grade_pct, direction=d, occupants=pr.occupants,
                    duration_s=pr.duration_s, initial_temp_C=pr.initial_temp_C, draws=uncertainty).rollaway_probability)
    return cols


def check(
    targets: Optional[List[str]] = typer.Argument(
        None, metavar="TARGET...",
        help="regulation presets (fmvss135, unr13h, paper30, or 'all') and, without --analytic, scenario "
             "TOML files; default: fmvss135 unr13h"),
    analytic: bool = typer.Option(False, "--analytic", help="use the paper's analytic check (no simulation)"),
    params: Optional[str] = opt.params_option(),
    uncertainty: Optional[int] = opt.uncertainty_option("with --analytic: N draws from the model file's covariance; adds "
                                                   "the roll-away probability of each case"),
    fmt: str = typer.Option("table", "--format", metavar="FORMAT",
                            help="csv | json | table (every row carries its verdict PASS/FAIL)"),
) -> int:
    """Regulation hold checks (the CI gate); exit 0 when every case holds, 1 when any fails.

    By default every scenario is simulated in MuJoCo and fails if the car slips or skids;
    --analytic uses the paper's check instead.  Presets: fmvss135 (FMVSS 135 S7.12), unr13h
    (UN R13-H), paper30 (the paper's 30 % case).  --params applies to the presets; a scenario
    file names its own parameter set.
    """
    check_choice(fmt, FORMATS, "format")
    p = load_model(params)
    names = list(targets or DEFAULT_PRESETS)
    if names == ["all"]:
        names = list(PRESETS)
    if not analytic:
        from rollaway.cli.inputs import expect_scenario
        from rollaway.compliance import simulated_check  # the MuJoCo gate
        for n in names:
            if n not in PRESETS:
                expect_scenario(n, "check")
        return simulated_check(names, p if params else None, fmt)
    for n in names:
        if n not in PRESETS and n.lower().endswith(".toml"):
            raise UserError(f"'{n}' is a scenario file; --analytic checks the regulation presets "
                            f"({', '.join(PRESETS)}) — simulate the file with 'rollaway check {n}' (no --analytic) "
                            f"or check one case with 'rollaway hold'")
        get_preset(n)
    cols = analytic_rows(names, p, uncertainty)
    write_table(cols, fmt, precision=4)
    if fmt == "table":
        for n in names:
            typer.echo(f"  {n}: {get_preset(n).source}")
    failed = int(np.sum(np.array(cols["verdict"]) == "FAIL"))
    if fmt == "table":
        typer.echo(f"{len(cols['verdict']) - failed} passed, {failed} failed" if failed else
                   f"all {len(cols['verdict'])} cases hold")
    return 1 if failed else 0


def register(app: typer.Typer) -> None:
    app.command("check")(check)
