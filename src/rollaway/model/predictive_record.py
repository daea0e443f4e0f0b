"""A calibrated model's predictive record: the model file's ``[predictive]`` table.

What ``diagnose --save-model`` stores beside the covariance (:mod:`rollaway.uncertainty.bands`
explains how each value is measured; :mod:`rollaway.uncertainty.predictive` turns the record into
draws)::

    [predictive]
    model_error_rel_sd = 0.006         # leave-one-test-out relative torque error where margins are decided
    model_error_floor_rel_sd = 0.004   # the noise's resolution of that error: the least used beyond the tested range
    model_error_dof = 7                # tests − 1 (the error is drawn from a Student-t)
    model_error_edge_low = [0.004, 0.6]  # [rel_sd, distance]: the lowest tested force predicted from the others
    model_error_edge_high = [0.002, 0.4] # ... and the highest (three or more tested forces)
    model_error_start = [0.02, 120.0, 300.0]  # [rel_sd, full_s, zero_s]: the error at the start of a hold
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

KEYS = ("model_error_rel_sd", "model_error_floor_rel_sd", "model_error_dof", "model_error_tests",
        "model_error_edge_low", "model_error_edge_high", "model_error_start",
        "tested_hand_force_N", "tested_initial_temp_C", "tested_duration_s", "tested_directions", "alternatives")


def record(model_error: dict, validity: dict, alternatives=()) -> dict:
    """The ``[predictive]`` table from :func:`rollaway.uncertainty.bands.model_error` and ``validity``."""
    out = {"model_error_rel_sd": float(model_error["rel_sd"]), "model_error_dof": int(model_error["dof"]),
           "model_error_tests": int(model_error["tests"]),
           "model_error_floor_rel_sd": float(model_error.get("floor_rel_sd", 0.0)),
           "tested_hand_force_N": list(validity["hand_force_N"]),
           "tested_initial_temp_C": list(validity["initial_temp_C"]),
           "tested_duration_s": float(validity["duration_s"]), "tested_directions": list(validity["directions"])}
    for side, e in model_error.get("edges", {}).items():
        out[f"model_error_edge_{side}"] = [float(e["rel_sd"]), float(e["distance"])]
    if model_error.get("start"):
        st = model_error["start"]
        out["model_error_start"] = [float(st["rel_sd"]), float(st["full_s"]), float(st["zero_s"])]
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
    for key, top in (("model_error_rel_sd", 10.0), ("model_error_floor_rel_sd", 10.0),
                     ("tested_duration_s", math.inf)):
        if key in out and not (_real(out[key]) and 0 <= out[key] <= top and math.isfinite(out[key])):
            raise UserError(f"{where}: key 'predictive.{key}' must be a number ≥ 0"
                            + (f" and ≤ {top:g} (a relative error of the torque)" if math.isfinite(top) else "")
                            + f", got {out[key]!r}")
    for key in ("model_error_dof", "model_error_tests"):
        v = out.get(key)
        if v is not None and not (isinstance(v, int) and not isinstance(v, bool) and v >= 1):
            raise UserError(f"{where}: key 'predictive.{key}' must be a whole number ≥ 1, got {v!r}")
    for key in ("model_error_edge_low", "model_error_edge_high"):
        v = out.get(key)
        if v is not None and not (isinstance(v, list) and len(v) == 2 and all(_real(x) and math.isfinite(x) for x in v)
                                  and 0 <= v[0] <= 10 and v[1] > 0):
            raise UserError(f"{where}: key 'predictive.{key}' must be [relative error ≥ 0, distance > 0], e.g. "
                            f"[0.004, 0.6]; got {v!r}")
    v = out.get("model_error_start")
    if v is not None and not (isinstance(v, list) and len(v) == 3 and all(_real(x) and math.isfinite(x) for x in v)
                              and 0 <= v[0] <= 10 and 0 <= v[1] <= v[2]):
        raise UserError(f"{where}: key 'predictive.model_error_start' must be [relative error ≥ 0, full_s ≥ 0, "
                        f"zero_s ≥ full_s], e.g. [0.02, 120.0, 300.0]; got {v!r}")
    for key in ("tested_hand_force_N", "tested_initial_temp_C"):
        v = out.get(key)
        if v is not None and not (isinstance(v, list) and len(v) == 2 and all(_real(x) and math.isfinite(x) for x in v)
                                  and v[0] <= v[1]):
            raise UserError(f"{where}: key 'predictive.{key}' must be [lowest, highest], finite numbers, e.g. "
                            f"[190.0, 350.0]; got {v!r}")
    dirs = out.get("tested_directions")
    if dirs is not None and not (isinstance(dirs, list) and set(dirs) <= {"downhill", "uphill"} and dirs):
        raise UserError(f"{where}: key 'predictive.tested_directions' must list \"downhill\" and/or \"uphill\"")
    alts = _alternatives(out.get("alternatives", []), where, base_dir)
    if alts:
        out["alternatives"] = alts
    return out


def _real(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _alternatives(entries, where: str, base_dir: Path | None) -> list[dict]:
    """The competing effect sets: each ``{ weight, file }`` once, an existing file other than the model's (its
    content is checked by :mod:`rollaway.model.model_file`, which reads it)."""
    if not isinstance(entries, list):
        raise UserError(f"{where}: key 'predictive.alternatives' must be a list of {{ weight = 0 < w < 1, file = "
                        f"\"other-model.toml\" }}, got {entries!r}")
    alts, seen = [], {}
    for i, a in enumerate(entries):
        key = f"predictive.alternatives[{i}]"
        if not (isinstance(a, dict) and isinstance(a.get("file"), str) and _real(a.get("weight"))
                and 0 < a["weight"] < 1 and set(a) <= {"weight", "file"}):
            raise UserError(f"{where}: key '{key}' must be {{ weight = 0 < w < 1, file = \"other-model.toml\" }} (no "
                            f"other keys), got {a!r}")
        path = Path(a["file"]) if base_dir is None or Path(a["file"]).is_absolute() else base_dir / a["file"]
        if not path.is_file():
            raise UserError(f"{where}: key '{key}.file': '{path}' does not exist; keep the alternative model files "
                            f"beside the model file (diagnose --save-model writes them)")
        real = path.resolve()
        if where.endswith(".toml") and real == Path(where).resolve():
            raise UserError(f"{where}: key '{key}.file' names this model file itself; an alternative is another "
                            f"effect set — delete the entry")
        if real in seen:
            raise UserError(f"{where}: key '{key}.file' names '{a['file']}' again (also alternatives[{seen[real]}]); "
                            f"list each alternative once with its whole weight")
        seen[real] = i
        alts.append({"weight": float(a["weight"]), "file": str(path)})
    if sum(a["weight"] for a in alts) >= 1:
        raise UserError(f"{where}: key 'predictive.alternatives': the weights add up to ≥ 1; the model itself keeps "
                        f"1 − Σ weights")
    return alts


__all__ = ["KEYS", "record", "validate"]
