"""Regulation checks: the CI gate (MuJoCo) and the paper's analytic check of the presets.

:func:`run_check` is ``rollaway check`` and :func:`rollaway.check`.  Without ``analytic`` it is the
gate: it simulates the regulation scenarios in MuJoCo and passes only if none slips or skids.  Targets are regulation
presets (default ``fmvss135`` and ``unr13h``: 400 N, 20 %, laden, facing up- and downhill) and/or
scenario TOML files.  Each scenario is simulated once (identical cases of two presets share
one simulation); the table shows the analytic margins next to the simulated outcome, and
the command's exit code is 0 only when every scenario holds, 1 otherwise (with the failing rows), 2 for
a bad target.  With ``analytic`` every preset case is checked by :func:`rollaway.hold.analytic_verdict`.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

from rollaway.errors import UserError, check_choice
from rollaway.hold import analytic_verdict
from rollaway.model.parameters import BrakeParameters
from rollaway.hold.regulations import PRESETS, get_preset
from rollaway.hold.scenario import Scenario, load_scenario, preset_scenarios
from rollaway.sweep.analytic import analytic_pass
from rollaway.sweep.executors import make_task, run_task, scenario_to_dict
from rollaway.model.drum_model import as_model
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


def analytic_rows(preset_names, params, uncertainty: int | None = None) -> dict[str, list]:
    """The paper's analytic check of each preset case (one row per preset and facing)."""
    cols: dict[str, list] = {k: [] for k in (
        "preset", "direction", "grade_pct", "occupants", "hand_force_N", "duration_s", "min_brake_margin",
        "tyre_margin", "min_hand_force_N", "verdict", "reason")}
    if uncertainty is not None:
        cols["rollaway_probability"] = []
        cols["beyond_bench_data"] = []
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
                from rollaway.uncertainty.draws import rollaway_risk
                risk = rollaway_risk(params, hand_force_N=pr.hand_force_N, grade_pct=pr.grade_pct, direction=d,
                                     occupants=pr.occupants, duration_s=pr.duration_s,
                                     initial_temp_C=pr.initial_temp_C, draws=uncertainty)
                cols["rollaway_probability"].append(risk.rollaway_probability)
                cols["beyond_bench_data"].append("; ".join(risk.flags))
                doubt = risk.not_sure(v.holds)          # the band gives the other answer ≥ 5 %: say so
                if doubt:
                    cols["reason"][-1] = f"{v.reason} at the calibrated values; {doubt}"
    return cols


@dataclass(frozen=True)
class CheckResult:
    """The rows of a regulation check, each with its verdict ``PASS``/``FAIL`` and reason.

    Attributes
    ----------
    columns : dict of str to list
        The table, column by column (``verdict``, ``reason``, margins, ...).
    targets : list of str
        The presets and scenario files checked.
    analytic : bool
        True for the paper's analytic check, False for the MuJoCo gate.
    """

    columns: dict
    targets: list
    analytic: bool

    @property
    def passed(self) -> bool:
        """True when every case holds."""
        return "FAIL" not in self.columns["verdict"]

    @property
    def failed(self) -> list[int]:
        """Row numbers of the failing cases."""
        return [i for i, v in enumerate(self.columns["verdict"]) if v == "FAIL"]

    def table(self):
        """The rows as a :class:`pandas.DataFrame`."""
        import pandas as pd
        return pd.DataFrame(self.columns)

    def _repr_html_(self) -> str:  # notebooks
        head = "<p><b>" + ("all cases hold" if self.passed else f"{len(self.failed)} cases fail") + "</b></p>"
        return head + self.table().to_html(index=False)


def run_check(targets=(), model=None, *, analytic: bool = False, uncertainty: int | None = None) -> CheckResult:
    """Check regulation presets (and, simulated, scenario files) with a drum model (None: the paper set).

    Targets: preset names (``fmvss135``, ``unr13h``, ``paper30``; ``"all"`` for every preset) and,
    without *analytic*, scenario TOML files (each names its own model); default: fmvss135, unr13h.
    *uncertainty*: with *analytic*, N draws from the model's covariance give each case's roll-away
    probability.
    """
    names = list(targets or DEFAULT_TARGETS)
    if names == ["all"]:
        names = list(PRESETS)
    if not analytic:
        return CheckResult(gate_table(gate_scenarios(names, model)), names, False)
    for n in names:
        if n not in PRESETS and n.lower().endswith(".toml"):
            raise UserError(f"'{n}' is a scenario file; --analytic checks the regulation presets "
                            f"({', '.join(PRESETS)}) — simulate the file with 'rollaway check {n}' (no --analytic) "
                            f"or check one case with 'rollaway hold'")
        get_preset(n)
    return CheckResult(analytic_rows(names, as_model(model), uncertainty), names, True)
