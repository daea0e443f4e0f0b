"""The CI gate: simulate the regulation scenarios in MuJoCo; pass only if none slips or skids.

``rollaway check`` (without ``--analytic``) runs :func:`simulated_check`.  Targets are regulation
presets (default ``fmvss135`` and ``unr13h``: 400 N, 20 %, laden, facing up- and downhill) and/or
scenario TOML files.  Each scenario is simulated once (identical cases of two presets share
one simulation); the table shows the analytic margins next to the simulated outcome, and
the exit code is 0 only when every scenario holds, 1 otherwise (with the failing rows), 2 for
a bad target.
"""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import typer

from rollaway.cli.output import write_table
from rollaway.errors import UserError, check_choice
from rollaway.parameters import BrakeParameters
from rollaway.regulations import PRESETS, get_preset
from rollaway.scenario import Scenario, load_scenario, preset_scenarios
from rollaway.sweep.analytic import analytic_pass
from rollaway.sweep.executors import make_task, run_task, scenario_to_dict
from rollaway.model import as_model
from rollaway.sweep.spec import DEFAULT_BAND, expand

DEFAULT_TARGETS = ("fmvss135", "unr13h")


def is_scenario_file(target: str) -> bool:
    return target.endswith(".toml") or Path(target).exists() or "/" in target or "\\" in target


def gate_scenarios(targets, params: BrakeParameters | None = None) -> list[tuple[str, Scenario]]:
    """(target, scenario) pairs: each preset gives one scenario per direction; a file gives one.

    *params*, when given, is the parameter set of the presets (each keeps its initial drum
    temperature); a scenario file names its own set (its ``params`` key).
    """
    out = []
    for t in targets:
        if is_scenario_file(t):
            out.append((Path(t).name, load_scenario(t)))     # a file carries its own parameters
            continue
        check_choice(t, PRESETS, "regulation preset or scenario file (.toml)")
        pr = get_preset(t)
        for s in preset_scenarios(t):
            if params is not None:    # a parameter set or a drum model (its effects apply to the presets)
                model = as_model(params)
                p = model.params.replace(initial_drum_temp_C=pr.initial_temp_C)
                s = dataclasses.replace(s, params=p, model=model.with_params(p))
            out.append((t, s))
    return out


def _reason(row) -> str:
    if row["error"]:
        return f"simulation failed: {row['error']}"
    t = row["rollaway_time_s"]
    at = f" at t = {t:.3g} s" if t == t else ""
    if row["outcome"] == "brake_slip":
        return f"brake slips{at} (simulated); analytic brake margin {row['brake_margin_min']:.3f}"
    if row["outcome"] == "tyre_skid":
        return (f"rear tyres skid{at} (simulated); adhesion margin {row['tyre_margin']:.3f} "
                f"(the paper's 1D check ignores tyres)")
    return "holds"


def gate_table(pairs: list[tuple[str, Scenario]]) -> dict[str, list]:
    """Simulate each distinct scenario once; one row per (target, scenario)."""
    cache: dict[str, dict] = {}
    cols: dict[str, list] = {k: [] for k in (
        "target", "scenario", "direction", "grade_pct", "occupants", "hand_force_N", "duration_s",
        "brake_margin_min", "tyre_margin", "sim_outcome", "rollaway_time_s", "max_displacement_m", "verdict",
        "reason")}
    for target, s in pairs:
        row = analytic_pass(s, expand(s, None, [{}]), DEFAULT_BAND).iloc[0].to_dict()
        pid = row["point_id"]
        if pid not in cache:
            cache[pid] = run_task(make_task(pid, scenario_to_dict(s), {}))
        rec = cache[pid]
        if rec["error"].startswith("UserError: "):      # the scenario is bad input, not a failing brake
            raise UserError(f"{s.source or target}: {rec['error'].removeprefix('UserError: ')}")
        row.update(outcome=rec.get("sim_outcome", ""), rollaway_time_s=rec.get("sim_rollaway_time_s") or float("nan"),
                   error=rec["error"])
        values = {"target": target, "scenario": s.name, "direction": s.direction, "grade_pct": s.grade_pct,
                  "occupants": s.occupants, "hand_force_N": s.hand_force_N, "duration_s": s.duration_s,
                  "brake_margin_min": row["brake_margin_min"], "tyre_margin": row["tyre_margin"],
                  "sim_outcome": row["outcome"] or "error", "rollaway_time_s": row["rollaway_time_s"],
                  "max_displacement_m": float(rec.get("sim_max_displacement_m") or float("nan")),
                  "verdict": "PASS" if row["outcome"] == "held" and not rec["error"] else "FAIL",
                  "reason": _reason(row)}
        for k, v in values.items():
            cols[k].append(v)
    return cols


def simulated_check(names, params: BrakeParameters | None, fmt: str) -> int:
    """Run the gate on *names* (presets and/or scenario files); print the table; 0 pass, 1 fail."""
    pairs = gate_scenarios(list(names or DEFAULT_TARGETS), params)
    cols = gate_table(pairs)
    if fmt == "table":      # the screen table: the columns that decide, short names (csv/json keep them all)
        short = {"scenario": "scenario", "grade_pct": "grade %", "occupants": "occ.", "hand_force_N": "force N",
                 "brake_margin_min": "brake margin", "tyre_margin": "tyre margin", "sim_outcome": "simulated",
                 "verdict": "verdict"}
        write_table({v: cols[k] for k, v in short.items()}, fmt, precision=3)
    else:
        write_table(cols, fmt, precision=4)
    failed = [i for i, v in enumerate(cols["verdict"]) if v == "FAIL"]
    say = (lambda m: typer.echo(m)) if fmt == "table" else (lambda m: print(m, file=sys.stderr))
    if fmt == "table":
        for n in dict.fromkeys(t for t, _ in pairs):
            if n in PRESETS:
                say(f"  {n}: {get_preset(n).source}")
    if not failed:
        say(f"all {len(pairs)} scenarios hold in the MuJoCo simulation")
        return 0
    say(f"{len(failed)} of {len(pairs)} scenarios roll away in the MuJoCo simulation:")
    for i in failed:
        say(f"  FAIL {cols['target'][i]} / {cols['scenario'][i]} (facing {cols['direction'][i]}, "
            f"{cols['grade_pct'][i]:g} %, {cols['hand_force_N'][i]:g} N): {cols['reason'][i]}")
    return 1
