"""A calibrated model's predictive record: the model file's ``[predictive]`` table.

What ``diagnose --save-model`` stores beside the covariance (:mod:`rollaway.uncertainty.bands`
explains how each value is measured; :mod:`rollaway.uncertainty.predictive` turns the record into
draws)::

    [predictive]
    model_error_rel_sd = 0.006         # leave-one-test-out relative torque error where margins are decided
    model_error_floor_rel_sd = 0.004   # the noise's resolution of that error: the least used beyond the tested range
    model_error_dof = 7                # tests − 1 (the error is drawn from a Student-t)
    tested_hand_force_N = [190.0, 350.0]
    tested_initial_temp_C = [104.2, 296.0]
    tested_duration_s = 3600.0
    tested_directions = ["downhill", "uphill"]
    alternatives = [{ weight = 0.3, file = "calibrated.alt1.toml" }]   # competing effect sets

:func:`record` builds the table, :func:`validate` checks one read from a file.
"""
from __future__ import annotations

import math
from pathlib import Path

from rollaway.errors import UserError, suggest

KEYS = ("model_error_rel_sd", "model_error_floor_rel_sd", "model_error_dof", "model_error_tests", "tested_hand_force_N", "tested_initial_temp_C",
        "tested_duration_s", "tested_directions", "alternatives")


def record(model_error: dict, validity: dict, alternatives=()) -> dict:
    """The ``[predictive]`` table from :func:`rollaway.uncertainty.bands.model_error` and ``validity``."""
    out = {"model_error_rel_sd": float(model_error["rel_sd"]), "model_error_dof": int(model_error["dof"]),
           "model_error_tests": int(model_error["tests"]),
           "model_error_floor_rel_sd": float(model_error.get("floor_rel_sd", 0.0)),
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
    for key in ("model_error_rel_sd", "model_error_floor_rel_sd", "tested_duration_s"):
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


__all__ = ["KEYS", "record", "validate"]
