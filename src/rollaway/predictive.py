"""A calibrated model's predictive record: model error, tested range, competing effect sets.

What ``diagnose --save-model`` stores beside the covariance (the model file's ``[predictive]``
table, :mod:`rollaway.identify.bands` explains how each value is measured)::

    [predictive]
    model_error_rel_sd = 0.006         # leave-one-test-out relative torque error where margins are decided
    model_error_dof = 7                # tests − 1 (the error is drawn from a Student-t)
    tested_hand_force_N = [190.0, 350.0]
    tested_initial_temp_C = [104.2, 296.0]
    tested_duration_s = 3600.0
    tested_directions = ["downhill", "uphill"]
    alternatives = [{ weight = 0.3, file = "calibrated.alt1.toml" }]   # competing effect sets

:func:`extrapolation` says how far a road question lies outside the tested range (and flags
it); :func:`model_error_draws` turns the record into one multiplicative torque error per draw.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rollaway.errors import UserError, suggest

KEYS = ("model_error_rel_sd", "model_error_dof", "model_error_tests", "tested_hand_force_N", "tested_initial_temp_C",
        "tested_duration_s", "tested_directions", "alternatives")
SPAN_FLOOR = {"hand_force_N": 50.0, "initial_temp_C": 50.0}     # a single tested value still has a scale [assumed]
TOLERANCE = 0.02             # within 2 % of the span of a tested edge counts as tested


def record(model_error: dict, validity: dict, alternatives=()) -> dict:
    """The ``[predictive]`` table from :func:`rollaway.identify.bands.model_error` and ``validity``."""
    out = {"model_error_rel_sd": float(model_error["rel_sd"]), "model_error_dof": int(model_error["dof"]),
           "model_error_tests": int(model_error["tests"]),
           "tested_hand_force_N": list(validity["hand_force_N"]),
           "tested_initial_temp_C": list(validity["initial_temp_C"]),
           "tested_duration_s": float(validity["duration_s"]), "tested_directions": list(validity["directions"])}
    if alternatives:
        out["alternatives"] = [dict(a) for a in alternatives]
    return out


def validate(table, where: str, base_dir: Path | None = None) -> dict:
    """Check a ``[predictive]`` table read from a model file (one-line errors naming the key)."""
    if not isinstance(table, dict):
        raise UserError(f"{where}: [predictive] must be a table")
    for key in table:
        if key not in KEYS:
            raise UserError(f"{where}: unknown key 'predictive.{key}'{suggest(key, KEYS)}")
    out = dict(table)
    for key in ("model_error_rel_sd", "tested_duration_s"):
        if key in out and (not isinstance(out[key], (int, float)) or isinstance(out[key], bool) or out[key] < 0
                           or not math.isfinite(out[key])):
            raise UserError(f"{where}: key 'predictive.{key}' must be a number ≥ 0")
    for key in ("tested_hand_force_N", "tested_initial_temp_C"):
        v = out.get(key)
        if v is not None and not (isinstance(v, list) and len(v) == 2 and all(isinstance(x, (int, float)) for x in v)
                                  and v[0] <= v[1]):
            raise UserError(f"{where}: key 'predictive.{key}' must be [lowest, highest], e.g. [190.0, 350.0]")
    dirs = out.get("tested_directions")
    if dirs is not None and not (isinstance(dirs, list) and set(dirs) <= {"downhill", "uphill"} and dirs):
        raise UserError(f"{where}: key 'predictive.tested_directions' must list \"downhill\" and/or \"uphill\"")
    alts = []
    for i, a in enumerate(out.get("alternatives", []) or []):
        if not (isinstance(a, dict) and isinstance(a.get("file"), str) and isinstance(a.get("weight"), (int, float))
                and 0 < a["weight"] < 1):
            raise UserError(f"{where}: key 'predictive.alternatives[{i}]' must be {{ weight = 0 < w < 1, "
                            f"file = \"other-model.toml\" }}")
        path = Path(a["file"]) if base_dir is None or Path(a["file"]).is_absolute() else base_dir / a["file"]
        if not path.is_file():
            raise UserError(f"{where}: key 'predictive.alternatives[{i}].file': '{path}' does not exist; keep the "
                            f"alternative model files beside the model file (diagnose --save-model writes them)")
        alts.append({"weight": float(a["weight"]), "file": str(path)})
    if sum(a["weight"] for a in alts) >= 1:
        raise UserError(f"{where}: key 'predictive.alternatives': the weights add up to ≥ 1; the model itself keeps "
                        f"1 − Σ weights")
    if alts:
        out["alternatives"] = alts
    return out


def extrapolation(pred: dict, *, hand_force_N: float, direction: str, initial_temp_C: float,
                  duration_s: float) -> tuple[float, list[str]]:
    """(factor ≥ 1 on the model error, flags) for a road question against the tested range."""
    factor, flags = 1.0, []
    for key, value, unit in (("hand_force_N", hand_force_N, "N"), ("initial_temp_C", initial_temp_C, "°C")):
        rng = pred.get(f"tested_{key}")
        if rng is None:
            continue
        lo, hi = rng
        span = max(hi - lo, SPAN_FLOOR[key])
        dist = max(lo - value, value - hi, 0.0)
        if dist > TOLERANCE * span:
            name = "hand force" if key == "hand_force_N" else "start temperature T_0"
            flags.append(f"{name} {value:g} {unit} is outside the tested {lo:g}–{hi:g} {unit}")
            factor += dist / span
    dirs = pred.get("tested_directions")
    if dirs and direction not in dirs:
        flags.append(f"facing {direction} was not tested (only {', '.join(dirs)})")
        factor += 1.0
    t_max = pred.get("tested_duration_s")
    if t_max and duration_s > (1 + TOLERANCE) * t_max:
        flags.append(f"a hold of {duration_s:g} s is longer than the bench's {t_max:g} s")
        factor += (duration_s - t_max) / t_max
    return factor, flags


def model_error_draws(pred: dict, n: int, factor: float, rng: np.random.Generator) -> np.ndarray:
    """n multiplicative torque errors ε (torque × (1 + ε)), Student-t with the record's dof, scaled by *factor*."""
    sd = float(pred.get("model_error_rel_sd", 0.0)) * factor
    if sd <= 0.0:
        return np.zeros(n)
    dof = max(int(pred.get("model_error_dof", 1)), 1)
    eps = sd * rng.standard_t(dof, n)
    return np.clip(eps, -0.9, 9.0)       # a torque never changes sign through its model error


__all__ = ["extrapolation", "model_error_draws", "record", "validate"]
