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
TRANSDUCER_REL_SD = 0.001   # [assumed] the bench torque transducer's gain uncertainty (a class-0.1 % calibration):
                             # common to every test, so no held-out score sees it, and it scales every road torque
MAX_LEVEL_DISTANCE = 10.0    # a hand force at or below the one where the torque vanishes: the error is at most this far
TOLERANCE = 0.02             # within 2 % of the span of a tested edge counts as tested
UNSEEN_HOLD_SHARE = 0.3      # [assumed] the relative torque error of a hold longer than the bench's, as a share of
                             # the change the model predicts over the untested part (:func:`hold_sd`): creep laws and
                             # a radiating drum's cooling carried from 2-min tests to an hour erred by 0.2–0.4 of it
                             # (tests/uncertainty/test_predictive.py)
HOLD_SD_CAP = 3.0            # [assumed] the most the hold's error counts (1σ, a share of the torque left): a
                             # model whose torque the hour's cooling nearly takes may leave the truth several times
                             # its torque (light pulls carried from 12-s to 2-min tests kept 2.5–4 times the torque
                             # their models did: tests/uncertainty/band_questions.py short campaigns 8 and 38); ε is
                             # clipped at −0.9 and +9 (model_error_draws): beyond this the band says "not sure"


def force_distance(tested_N, hand_force_N: float, zero_torque_force_N: float | None = None,
                   level_ratio: float | None = None) -> float:
    """How far *hand_force_N* lies outside the tested hand forces *tested_N* = [lowest, highest], relative to their
    span (at least :data:`SPAN_FLOOR`); 0 within :data:`TOLERANCE` of the span.  Below the tested forces the torque
    falls towards zero, and a relative error grows as the torque level falls: there the distance is at least the
    torque level's ratio less one (capped at :data:`MAX_LEVEL_DISTANCE`) — the ratio (F_lo − F₀)/(F − F₀) of the
    clamp displacements, F₀ = *zero_torque_force_N* (eq. 24: u₆ = 0), or *level_ratio*, the model's own least torque
    at F_lo over that at F under the question's conditions (:func:`rollaway.uncertainty.draws.torque_level_ratio`:
    the thermal terms and the effects count too), whichever is larger."""
    lo, hi = tested_N
    span = max(hi - lo, SPAN_FLOOR["hand_force_N"])
    dist = max(lo - hand_force_N, hand_force_N - hi, 0.0)
    if dist <= TOLERANCE * span:
        return 0.0
    rel = dist / span
    if hand_force_N < lo:
        levels = [1.0 if level_ratio is None or np.isnan(level_ratio) else level_ratio]   # inf: no torque at F
        if zero_torque_force_N is not None and lo > zero_torque_force_N:
            levels.append((lo - zero_torque_force_N) / max(hand_force_N - zero_torque_force_N, 1e-9))
        rel = max(rel, min(max(levels) - 1.0, MAX_LEVEL_DISTANCE))
    return rel


def extrapolation(pred: dict, *, hand_force_N: float, direction: str, initial_temp_C: float,
                  duration_s: float, zero_torque_force_N: float | None = None,
                  level_ratio: float | None = None) -> tuple[float, list[str]]:
    """(factor ≥ 1 on the model error, flags) for a road question against the tested range.

    Each distance counts relative to the tested span; the hand force's by :func:`force_distance`."""
    factor, flags = 1.0, []
    rng = pred.get("tested_hand_force_N")
    if rng is not None:
        rel = force_distance(rng, hand_force_N, zero_torque_force_N, level_ratio)
        if rel > 0.0:
            flags.append(f"hand force {hand_force_N:g} N is outside the tested {rng[0]:g}–{rng[1]:g} N")
            factor += rel
    rng = pred.get("tested_initial_temp_C")
    if rng is not None:
        lo, hi = rng
        span = max(hi - lo, SPAN_FLOOR["initial_temp_C"])
        dist = max(lo - initial_temp_C, initial_temp_C - hi, 0.0)
        if dist > TOLERANCE * span:
            flags.append(f"start temperature T_0 {initial_temp_C:g} °C is outside the tested {lo:g}–{hi:g} °C")
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


def edge_sd(pred: dict, hand_force_N: float, zero_torque_force_N: float | None = None,
            level_ratio: float | None = None) -> float:
    """The relative torque error the bench itself showed when it extrapolated in hand force (the record's
    ``model_error_edge_low``/``_high`` = [rel_sd, distance]: the edge force predicted from the others), scaled to
    the question's distance d beyond that edge (:func:`force_distance`) by r = d/distance, and by r² beyond it: the
    calibration takes the level and the slope of a misfit in hand force (eq. (24)'s offset and slope), so what is
    left grows with the square of the distance; r within it (no narrower than the measured error's linear share).
    0 inside the tested forces."""
    rng = pred.get("tested_hand_force_N")
    if rng is None:
        return 0.0
    dist = force_distance(rng, hand_force_N, zero_torque_force_N, level_ratio)
    edge = pred.get("model_error_edge_low" if hand_force_N < rng[0] else "model_error_edge_high")
    if dist <= 0.0 or not edge or edge[1] <= 0.0:
        return 0.0
    r = dist / float(edge[1])
    return float(edge[0]) * max(r, r * r)


def measured_factor(pred: dict, factor: float, hand_force_N: float, zero_torque_force_N: float | None = None,
                    level_ratio: float | None = None) -> float:
    """The extrapolation *factor* on the measured model error ``rel_sd`` (:func:`model_error_sd`): less the share of
    the hand-force distance (:func:`force_distance`) that the bench's own extrapolation in hand force covered — the
    record's ``model_error_edge_low``/``_high`` measured the error of predicting the edge force from the others at
    its distance, and :func:`edge_sd` carries that error to the question.  Beyond that distance the factor grows
    again from there; without an edge record it is *factor*."""
    rng = pred.get("tested_hand_force_N")
    if rng is None:
        return factor
    dist = force_distance(rng, hand_force_N, zero_torque_force_N, level_ratio)
    edge = pred.get("model_error_edge_low" if hand_force_N < rng[0] else "model_error_edge_high")
    if dist <= 0.0 or not edge or edge[1] <= 0.0:
        return factor
    return max(factor - min(dist, float(edge[1])), 1.0)


def hold_sd(unseen_change: float) -> float:
    """The relative torque error of a hold longer than the bench's tests: :data:`UNSEEN_HOLD_SHARE` of
    *unseen_change*, the largest change of a model's torque after the end of the tested hold, relative to the
    torque left at that time (:func:`rollaway.uncertainty.draws.unseen_hold_change`).  The bench saw
    nothing of that change — the drum cooling on, a creep or a relaxation going on — so no held-out score measured
    how well the model's laws carry it; the error scales with how much the model must carry, not with the bench's
    noise (a dense log of short tests would otherwise give an hour's answer to a few parts in 10 000)."""
    return UNSEEN_HOLD_SHARE * max(float(unseen_change), 0.0)


def model_error_sd(pred: dict, factor: float, edge: float = 0.0, measured: float | None = None,
                   hold: float = 0.0) -> float:
    """The relative torque error's scale for a question with extrapolation *factor* (see :func:`model_error_draws`):
    √((rel_sd·measured)² + floor_rel_sd²·(UNSEEN² + (factor − 1)²) + hold²), and at least *edge* (:func:`edge_sd`:
    the error the bench showed when it extrapolated in hand force, at the question's distance); *measured*
    (:func:`measured_factor`) is *factor* unless the bench's own extrapolation in hand force covered part of it;
    *hold* (:func:`hold_sd`) the error of carrying the model beyond the bench's hold.

    The measured error (``rel_sd``) grows with the distance from the tested range.  An error the data could not
    see — below ``floor_rel_sd``, the noise's resolution of one test's held-out error — is counted too: a share
    :data:`UNSEEN` of the floor everywhere, and growing with the distance from the tested edge, so that a
    question just outside the tested range is as good as a tested one.  A record measured on a bench (one with
    ``model_error_rel_sd``) also carries the transducer's gain uncertainty :data:`TRANSDUCER_REL_SD`, which no
    held-out test can see: on a dense log the other terms can fall to a few parts in 10 000."""
    sd = float(pred.get("model_error_rel_sd", 0.0))
    floor = float(pred.get("model_error_floor_rel_sd", 0.0))
    gain = TRANSDUCER_REL_SD if "model_error_rel_sd" in pred else 0.0
    grown = sd * (factor if measured is None else measured)
    return max(float(np.sqrt(grown ** 2 + floor ** 2 * (UNSEEN ** 2 + max(factor - 1.0, 0.0) ** 2) + gain ** 2
                             + hold ** 2)), float(edge))


def model_error_draws(pred: dict, n: int, factor: float, rng: np.random.Generator, edge: float = 0.0,
                      measured: float | None = None, hold: float = 0.0) -> np.ndarray:
    """n multiplicative torque errors ε (torque × (1 + ε)) of scale :func:`model_error_sd` (widened beyond the
    tested range by *factor*, at least *edge*; *measured*: :func:`measured_factor`; *hold*: :func:`hold_sd`).

    What is measured or extrapolated — ``rel_sd``·measured, the floor's growth with the distance beyond the tested
    range, or *edge* where that decides — is Student-t with the record's dof: a scale estimated from a handful of
    held-out tests, and stretched beyond them.  The share of the floor counted at every question
    (:data:`UNSEEN`), the transducer's gain and the error beyond the bench's hold (*hold*) are assumed magnitudes,
    not estimates: Gaussian, independent of the rest.  (The Student-t on the growth keeps the 135 N questions, where the torque nearly vanishes, covered;
    a Student-t on the unseen share too widened every question inside the tested range for no measured miss.)"""
    sd = model_error_sd(pred, factor, edge, measured, hold)
    if sd <= 0.0:
        return np.zeros(n)
    dof = max(int(pred.get("model_error_dof", 1)), 1)
    floor = float(pred.get("model_error_floor_rel_sd", 0.0))
    gain = TRANSDUCER_REL_SD if "model_error_rel_sd" in pred else 0.0
    assumed = float(np.sqrt((UNSEEN * floor) ** 2 + gain ** 2 + hold ** 2))
    if edge > 0.0 and float(edge) >= sd or assumed >= sd:
        assumed = 0.0 if edge > 0.0 and float(edge) >= sd else sd
    stretched = float(np.sqrt(max(sd * sd - assumed * assumed, 0.0)))
    eps = stretched * rng.standard_t(dof, n) + assumed * rng.standard_normal(n)
    return np.clip(eps, -0.9, 9.0)       # a torque never changes sign through its model error


def start_weight(time_s, start) -> np.ndarray:
    """The weight of the start's error (the record's ``model_error_start`` = [rel_sd, full_s, zero_s]) at *time_s*:
    1 over the start samples' span (t ≤ full_s), falling linearly to 0 at the first sample after them (zero_s),
    0 after: what the bench measured at the start, and nothing between its samples said it ends sooner."""
    _, full, zero = (float(x) for x in start)
    t = np.asarray(time_s, float)
    if zero <= full:
        return (t <= full).astype(float)
    return np.clip((zero - t) / (zero - full), 0.0, 1.0)


def start_error_draws(pred: dict, n: int, factor: float, rng: np.random.Generator, edge: float = 0.0,
                      measured: float | None = None, hold: float = 0.0) -> np.ndarray | None:
    """n relative torque errors at the start of the hold beyond the model error drawn for the whole hold
    (:func:`model_error_draws`), or None where the record has none to add: the start's held-out error
    (``model_error_start``, :func:`rollaway.uncertainty.bands.start_error`), widened as the measured error is
    (*measured*, else *factor*), less the whole hold's scale (:func:`model_error_sd`) in quadrature — the start's
    error is at least its own, not the sum of both.  Student-t with the record's dof (a scale from a handful of
    tests)."""
    start = pred.get("model_error_start")
    if not start:
        return None
    grown = float(start[0]) * (factor if measured is None else measured)
    extra = grown ** 2 - model_error_sd(pred, factor, edge, measured, hold) ** 2
    if extra <= 0.0:
        return None
    dof = max(int(pred.get("model_error_dof", 1)), 1)
    return np.clip(np.sqrt(extra) * rng.standard_t(dof, n), -0.9, 9.0)


class StartError:
    """A margin function (:class:`rollaway.hold.numeric.MarginFunction`) with each point's start error *extra*
    (:func:`start_error_draws`) on its torque, weighted in time by :func:`start_weight` of the record's *start*."""

    def __init__(self, fn, extra: np.ndarray, start):
        self.fn, self.extra, self.start = fn, np.asarray(extra, float), start

    def __len__(self) -> int:
        return len(self.fn)

    def __call__(self, time_s, index, force_N=None):
        i = np.asarray(index, int)
        return self.fn(time_s, i, force_N) * (1.0 + self.extra[i] * start_weight(time_s, self.start))


__all__ = ["StartError", "edge_sd", "extrapolation", "force_distance", "hold_sd", "measured_factor",
           "model_error_draws", "model_error_sd", "record", "start_error_draws", "start_weight", "validate"]
