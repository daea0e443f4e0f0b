"""``rollaway check``: regulation hold checks (the MuJoCo gate, or the analytic check); :func:`rollaway.check`."""
from __future__ import annotations

import sys
from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.output import FORMATS, write_table
from rollaway.errors import check_choice
from rollaway.hold.regulations import PRESETS, get_preset

DEFAULT_PRESETS = ("fmvss135", "unr13h")
SHORT = {"scenario": "scenario", "grade_pct": "grade %", "occupants": "occ.", "hand_force_N": "force N",
         "brake_margin_min": "brake margin", "tyre_margin": "tyre margin", "sim_outcome": "simulated",
         "verdict": "verdict"}       # the gate's screen table: the columns that decide (csv/json keep them all)


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
    from rollaway.api import check as run_check

    check_choice(fmt, FORMATS, "format")
    if not analytic:
        opt.only_with("--analytic (check's analytic mode; the MuJoCo gate simulates the model as it is)",
                      **{"--uncertainty": uncertainty})
    if params is not None and targets and not any(t in PRESETS or t == "all" for t in targets):
        from rollaway.errors import UserError
        raise UserError(f"--params sets the drum model of the regulation presets, and no preset is given: each "
                        f"scenario file names its own model (its 'params' key) — set it there, add a preset "
                        f"({', '.join(PRESETS)}), or use 'rollaway simulate FILE --params {params}'")
    if not analytic:
        from rollaway.cli.inputs import expect_scenario
        for n in targets or ():
            if n not in PRESETS and n != "all":
                expect_scenario(n, "check")
    res = run_check(targets or (), model=params, analytic=analytic, uncertainty=uncertainty)
    cols = res.columns
    if fmt == "table" and not analytic:
        write_table({v: cols[k] for k, v in SHORT.items()}, fmt, precision=3)
    else:
        write_table(cols, fmt, precision=4)
    say = typer.echo if fmt == "table" else (lambda m: print(m, file=sys.stderr))
    if fmt == "table":
        for n in res.targets:
            if n in PRESETS:
                say(f"  {n}: {get_preset(n).source}")
    n, failed = len(cols["verdict"]), res.failed
    if analytic:
        if fmt == "table":
            say(f"{n - len(failed)} passed, {len(failed)} failed" if failed else f"all {n} cases hold")
    elif not failed:
        say(f"all {n} scenarios hold in the MuJoCo simulation")
    else:
        say(f"{len(failed)} of {n} scenarios roll away in the MuJoCo simulation:")
        for i in failed:
            say(f"  FAIL {cols['target'][i]} / {cols['scenario'][i]} (facing {cols['direction'][i]}, "
                f"{cols['grade_pct'][i]:g} %, {cols['hand_force_N'][i]:g} N): {cols['reason'][i]}")
    return 0 if res.passed else 1


def register(app: typer.Typer) -> None:
    app.command("check")(check)
