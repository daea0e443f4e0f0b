"""A predictive record in use: model-error draws, widened for questions beyond the tested range.

The record itself (the model file's ``[predictive]`` table) is :mod:`rollaway.model.predictive_record`;
:func:`extrapolation` says how far a road question lies outside the tested range (and flags
it); :func:`model_error_draws` turns the record into one multiplicative torque error per draw.
"""
from __future__ import annotations

import numpy as np

from rollaway.model.predictive_record import KEYS, record, validate  # noqa: F401  (the record, read here too)

SPAN_FLOOR = {"hand_force_N": 50.0, "initial_temp_C": 50.0}     # a single tested value still has a scale [assumed]
UNSEEN = 0.5                 # [assumed] the unseen model error counted inside the tested range, as a share of the
                             # floor: an error that size adds a quarter of the noise's variance to a held-out score
                             # (measured on tests/uncertainty/band_questions.py: 0.25 left 1-min bands at 0.88)
MAX_LEVEL_DISTANCE = 10.0    # a hand force at or below the one where the torque vanishes: the error is at most this far
TOLERANCE = 0.02             # within 2 % of the span of a tested edge counts as tested


def extrapolation(pred: dict, *, hand_force_N: float, direction: str, initial_temp_C: float,
                  duration_s: float, zero_torque_force_N: float | None = None) -> tuple[float, list[str]]:
    """(factor ≥ 1 on the model error, flags) for a road question against the tested range.

    Each distance counts relative to the tested span.  Below the tested hand forces the torque falls
    towards zero at *zero_torque_force_N* (eq. 24: u₆ = 0), and a relative error grows as the torque level
    falls: there the distance is at least the torque level's ratio less one, (F_lo − F₀)/(F − F₀) − 1
    (capped at :data:`MAX_LEVEL_DISTANCE`)."""
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
            rel = dist / span
            if key == "hand_force_N" and value < lo and zero_torque_force_N is not None and lo > zero_torque_force_N:
                level = (lo - zero_torque_force_N) / max(value - zero_torque_force_N, 1e-9)
                rel = max(rel, min(level - 1.0, MAX_LEVEL_DISTANCE))
            factor += rel
    dirs = pred.get("tested_directions")
    if dirs and direction not in dirs:
        flags.append(f"facing {direction} was not tested (only {', '.join(dirs)})")
        factor += 1.0
    t_max = pred.get("tested_duration_s")
    if t_max and duration_s > (1 + TOLERANCE) * t_max:
        flags.append(f"a hold of {duration_s:g} s is longer than the bench's {t_max:g} s")
        factor += (duration_s - t_max) / t_max
    return factor, flags


def model_error_sd(pred: dict, factor: float) -> float:
    """The relative torque error's scale for a question with extrapolation *factor* (see :func:`model_error_draws`):
    √((rel_sd·factor)² + floor_rel_sd²·(UNSEEN² + (factor − 1)²)).

    The measured error (``rel_sd``) grows with the distance from the tested range.  An error the data could not
    see — below ``floor_rel_sd``, the noise's resolution of one test's held-out error — is counted too: a share
    :data:`UNSEEN` of the floor everywhere, and growing with the distance from the tested edge, so that a
    question just outside the tested range is as good as a tested one."""
    sd = float(pred.get("model_error_rel_sd", 0.0))
    floor = float(pred.get("model_error_floor_rel_sd", 0.0))
    return float(np.sqrt((sd * factor) ** 2 + floor ** 2 * (UNSEEN ** 2 + max(factor - 1.0, 0.0) ** 2)))


def model_error_draws(pred: dict, n: int, factor: float, rng: np.random.Generator) -> np.ndarray:
    """n multiplicative torque errors ε (torque × (1 + ε)), Student-t with the record's dof, of scale
    :func:`model_error_sd` (widened beyond the tested range by *factor*).  The floor's share (:data:`UNSEEN`) was
    measured with this Student-t: a Gaussian floor left 1-min bands at 135 N below 0.85."""
    sd = model_error_sd(pred, factor)
    if sd <= 0.0:
        return np.zeros(n)
    dof = max(int(pred.get("model_error_dof", 1)), 1)
    eps = sd * rng.standard_t(dof, n)
    return np.clip(eps, -0.9, 9.0)       # a torque never changes sign through its model error


__all__ = ["extrapolation", "model_error_draws", "model_error_sd", "record", "validate"]
