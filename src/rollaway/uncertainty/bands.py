"""Predictive bands of a calibrated model: what the parameter covariance does not know.

A fitted covariance says how well the data pin the parameters *of the chosen model*.  The road
question also depends on which effects were chosen and on how wrong the chosen forms are.
:func:`model_error`, :func:`alternatives` and :func:`validity` measure both, from the bench data themselves
(:func:`rollaway.model.predictive_record.record` turns them into the model file's ``[predictive]`` table):

* **model error** — every test is predicted by the model calibrated on the other tests
  (linearised leave-one-test-out, :func:`rollaway.uncertainty.heldout.loto_residuals`).  Each
  test's score is its relative torque error where its margin is decided (the third of its
  samples with the lowest predicted torque), less what a right model would give there: the
  measurement noise and the re-calibration without the test
  (:func:`rollaway.uncertainty.heldout.loto_parameter_variance`; that parameter error is drawn apart),
  each at the test's own share 1 − h of its score (:func:`_scored`: what the re-calibration amplified is not
  a road question's).  Their root mean square ``rel_sd`` (with ``dof`` = tests − 1) is a multiplicative torque
  error ε ~ rel_sd·t_dof drawn with every parameter draw: jackknife-style, distribution-free
  in its scores, Student-t in its use (a handful of tests cannot give a finite 90 % conformal
  quantile).  When the saved form is known to leave structure, the held-out tests saw that misfit
  only in part: ``rel_sd`` is widened — by :data:`MISFIT_INFLATION` where an effect is named
  "partial" (its flexible form clears the structure), by :data:`UNEXPLAINED_INFLATION` where no
  catalogue form does (both assumed).  ``floor_rel_sd`` is the resolution of those scores: the
  relative error one test's noise alone gives where its margin is decided.  A model error below it
  cannot be told from zero: beyond the tested range it grows with the distance from the tested edge
  (:func:`rollaway.uncertainty.predictive.model_error_sd`).  The start of each test, where a hot start
  can decide the margin, is scored apart (:func:`start_error`): the torque errs there by at least that
  (:func:`rollaway.uncertainty.predictive.start_error_draws`);
* **choice of effects** — competing effect sets the data cannot rule out (within
  :data:`COMPETING_BIC` of the selected one, and always those named beside the verdict as
  indistinguishable) get pseudo-BMA weights from their leave-one-test-out
  scores (Bayesian-bootstrap pseudo-BMA: w ∝ exp(−½·Σ score) averaged over Dirichlet reweightings
  of the tests; Yao et al. 2018, "Using stacking to average Bayesian predictive distributions",
  §3.1, with the Gaussian log score); draws are split among them, and each set's draws carry its own
  model error (its own held-out tests; where the verdict leaves structure, a catalogue form no less than the
  verdict's; a shape-free form by its own, beside the splines of the other quantities along the same covariate).
  The chosen effects' own forms compete too: the same set with each effect shape-free (:func:`rollaway.identify.shape.form_rivals`) is weighed
  the same way, so a catalogue form the residual cannot fault but the held-out tests do not prefer leaves
  its doubt in the band;
* **validity** — the tested hand forces, directions, start temperatures and hold duration.  A
  road question outside them is flagged and the model error is widened by
  :func:`rollaway.uncertainty.predictive.extrapolation` (hand force, T_0 and duration by their distance
  relative to the tested span, an untested direction by one span).
"""
from __future__ import annotations

import math

import numpy as np

from rollaway.uncertainty.heldout import (held_out, loto_parameter_variance, loto_residuals, loto_scores,
                                           parameter_variance)

COMPETING_BIC = 6.0          # effect sets within this ΔBIC of the selected one compete for weight
MIN_WEIGHT = 0.02            # lighter alternatives are dropped (weights renormalised)
MAX_RELATIVE_SE = 0.35       # an alternative's effect parameters must be sized at least this well
BOOTSTRAP = 1000             # Bayesian-bootstrap replicates of the per-test scores (BB-pseudo-BMA)
MISFIT_INFLATION = 2.5       # [assumed] a model whose form leaves structure errs beyond its held-out tests
UNEXPLAINED_INFLATION = 4.0  # [assumed] ... and more where no catalogue form clears the structure (measured on
                             # tests/uncertainty/band_questions.py, a sigmoid modulus drop at 1-min: 2.5 left
                             # bands whose centre was 1.3–2.2 half-widths from the truth)
MARGIN_SHARE = 1.0 / 3.0     # the share of a test's samples (lowest predicted torque) that decides its margin
START_WINDOW_S = 120.0       # [assumed] the start of a test whose held-out error is scored apart (start_error): the
                             # first minutes of a hot hold, where the lining cools fastest


def validity(data) -> dict:
    """What the bench covered: hand force [N], start temperature [°C], duration [s], directions."""
    t0 = data.test_initial_temp_C
    return {"hand_force_N": [float(np.min(data.hand_force_N)), float(np.max(data.hand_force_N))],
            "initial_temp_C": [float(np.min(t0)), float(np.max(t0))],
            "duration_s": float(np.max(data.time_s)),
            "directions": sorted({"downhill" if s > 0 else "uphill" for s in np.unique(data.sign)})}


def _margin_score(fit, k: int, loo_torque_Nm: np.ndarray, weights: np.ndarray,
                  start: bool = False) -> tuple[float, float] | None:
    """(score, noise variance) of test *k*: its mean relative held-out torque error over the
    :data:`MARGIN_SHARE` of its samples with the least predicted torque (*start*: over its samples of the first
    :data:`START_WINDOW_S`), and that mean's variance from the noise alone.  Writes the score's weights on the
    standardised residuals into *weights* (rows of [temperature | torque])."""
    d = fit.data
    n = len(d)
    pred = fit.prediction.torque_Nm
    rows = np.flatnonzero(d.test_index == k)
    if rows.size == 0:
        return None
    if start:
        low = rows[d.time_s[rows] <= np.min(d.time_s[rows]) + START_WINDOW_S]
    else:
        m = max(3, int(math.ceil(MARGIN_SHARE * rows.size)))
        low = rows[np.argsort(pred[rows])[:m]]
    level = np.maximum(np.abs(pred[low]), 1e-9)
    weights[n + low] = d.torque_sigma_Nm[low] / level / low.size          # score = Σ w·(standardised residual)
    return float(np.mean(loo_torque_Nm[low] / level)), float(np.sum(weights[n + low] ** 2))


def model_error(fit, misfit: bool | str = False) -> dict:
    """Relative torque error of leave-one-test-out predictions where each test's margin is decided
    (× :data:`MISFIT_INFLATION` when the model's form is known to leave structure, *misfit* true or
    ``"partial"``; × :data:`UNEXPLAINED_INFLATION` when *misfit* is ``"unexplained"``: no catalogue form clears it),
    and at each edge of the tested hand forces the error of predicting that force from the others
    (:func:`edge_error`)."""
    d = fit.data
    n = len(d)
    loo = loto_residuals(fit)[n:] * d.torque_sigma_Nm            # model − measured [N·m], own test held out
    scores, excess, floor, refit = _scored(fit, loo, False)
    rel_sd = math.sqrt(max(excess, 0.0))
    if misfit:
        rel_sd *= UNEXPLAINED_INFLATION if misfit == "unexplained" else MISFIT_INFLATION
    out = {"rel_sd": rel_sd, "dof": max(len(scores) - 1, 1), "tests": len(scores),
           "per_test": [float(x) for x in scores], "misfit": misfit, "floor_rel_sd": floor,
           "excess_ms": excess, "refit_ms": refit,
           "edges": {side: e for side in ("low", "high") if (e := edge_error(fit, side)) is not None}}
    start = start_error(fit, loo)
    if start is not None:
        out["start"] = start
    return out


def _scored(fit, loo: np.ndarray, start: bool) -> tuple[list, float, float, float]:
    """(per-test scores, mean squared score less the noise's and the re-calibration's share, the noise's resolution
    of one score, the re-calibration's mean share) of :func:`_margin_score` over the tests of *fit*.

    A model error held out with its test is amplified by the re-calibration without it as the noise is: the held-out
    residual is (I − H_gg)⁻¹ times the fitted one, and a test the others pin poorly (at the edge of the tested
    forces or start temperatures, alone in its direction) shows its error enlarged.  Each test's excess is counted
    at its own share, 1 − h = noise / (noise + re-calibration) of its score: the error of predicting a new test
    from all of them, not that of predicting this one from the others (on a linear model with an error per test that
    it lacks: 0.93–0.97 of a new test's mean square error, against 1.3 without the share)."""
    d = fit.data
    scores, noise, tests = [], [], []
    weights = np.zeros(2 * len(d))
    for k in range(d.n_tests):
        got = _margin_score(fit, k, loo, weights, start)
        if got is not None:
            scores.append(got[0])
            noise.append(got[1])
            tests.append(k)
    if not scores:
        return [], 0.0, 0.0, 0.0
    refit = loto_parameter_variance(fit, weights)[tests]
    noise = np.asarray(noise)
    own = noise / np.maximum(noise + refit, 1e-300)         # 1 − h: the share of a held-out score that is the test's own
    excess = float(np.mean((np.asarray(scores) ** 2 - noise - refit) * own))
    return scores, excess, math.sqrt(float(np.mean(noise))), float(np.mean(refit))


def start_error(fit, loo: np.ndarray | None = None) -> dict | None:
    """The relative torque error of leave-one-test-out predictions at the start of each test (its samples of the
    first :data:`START_WINDOW_S`), net of the noise and the re-calibration (as :func:`model_error`), with the share
    :data:`~rollaway.uncertainty.predictive.UNSEEN` of the noise's resolution of that score that the hold's error
    counts at every question too (:func:`rollaway.uncertainty.predictive.model_error_sd`): ``{"rel_sd",
    "excess_ms", "floor_rel_sd", "full_s", "zero_s"}``.  With one start sample a test (5- and 15-min sampling) that
    resolution is the noise of one sample, several times the hold's, and an error below it cannot be told from
    zero: a sigmoid modulus drop whose spline predicted its held-out starts within the noise was 4–10 % off between
    them (15-min band campaign 45).  A hot start can decide a hold's least margin (a friction or a lining
    modulus that recovers as the lining cools: the torque rises after the start), and the share of each test's
    samples with the least predicted torque that :func:`model_error` scores holds one start sample at most: where a
    temperature law bends between the tested start temperatures, a spline's start error came out at 2–11 % while
    that score stayed at the noise (two-effect, 5-min and 15-min campaigns of
    ``tests/uncertainty/band_questions.py`` whose bands missed at questions decided at the start).  *full_s*: the
    time the start samples span, *zero_s*: the first sample after them (medians over the tests); between them the
    start's error is drawn with a weight falling to zero (:func:`rollaway.uncertainty.predictive.start_weight`).
    None without sample times, with fewer than three tests or with one sample a test."""
    d = fit.data
    if getattr(d, "time_s", None) is None or d.n_tests < 3 or len(d) <= d.n_tests:
        return None
    if loo is None:
        loo = loto_residuals(fit)[len(d):] * d.torque_sigma_Nm
    from rollaway.uncertainty.predictive import UNSEEN
    _, excess, floor, _ = _scored(fit, loo, True)
    full, zero = [], []
    for k in range(d.n_tests):
        t = np.sort(d.time_s[d.test_index == k])
        if t.size:
            inside = t <= t[0] + START_WINDOW_S
            full.append(t[inside][-1] - t[0])
            zero.append(t[~inside][0] - t[0] if np.any(~inside) else t[-1] - t[0])
    return {"rel_sd": math.sqrt(max(excess, 0.0) + (UNSEEN * floor) ** 2), "excess_ms": excess, "floor_rel_sd": floor,
            "full_s": float(np.median(full)),
            "zero_s": float(max(np.median(zero), np.median(full)))}


def edge_error(fit, side: str) -> dict | None:
    """The relative torque error of predicting the tests at the lowest (*side* ``"low"``) or highest tested hand
    force from the model calibrated on the others — an extrapolation in hand force the data made — net of the noise
    and of the re-calibration (as :func:`model_error`): ``{"rel_sd", "distance", "tests", "excess_ms",
    "floor_rel_sd"}``, *distance* that extrapolation's (:func:`rollaway.uncertainty.predictive.force_distance` from
    the other forces' range).  At the low edge ``rel_sd`` counts the share
    :data:`~rollaway.uncertainty.predictive.UNSEEN` of the noise's resolution of those scores, as the hold's error
    does: below the tested forces the torque falls towards zero, and an error in the clamp that does not scale with
    the force (too little clamp lost on cooling), within the noise at the lowest tested force, grows relative to
    the torque (:func:`rollaway.uncertainty.predictive.edge_sd` carries it with the square of the distance).  Above
    the tested forces such an error shrinks relative to the torque, and the high edge counts what it measured.
    None without a Jacobian or with fewer than three tested hand forces (two cannot be extrapolated from one)."""
    from rollaway.uncertainty.predictive import force_distance
    d = fit.data
    if fit.jacobian is None or not fit.names or getattr(d, "hand_force_N", None) is None:
        return None
    per_test = np.array([d.hand_force_N[d.test_index == k][0] if np.any(d.test_index == k) else np.nan
                         for k in range(d.n_tests)])
    levels = np.unique(np.round(per_test[np.isfinite(per_test)], 1))
    if levels.size < 3:
        return None
    edge, rest = (levels[0], levels[1:]) if side == "low" else (levels[-1], levels[:-1])
    held = np.flatnonzero(np.abs(per_test - edge) < 0.05)
    g, loo_g, solve = held_out(fit, held)
    n = len(d)
    loo = np.zeros(2 * n)
    loo[g] = loo_g
    loo_torque = loo[n:] * d.torque_sigma_Nm
    s2, noise, refit = [], [], []
    for k in held:
        weights = np.zeros(2 * n)
        got = _margin_score(fit, int(k), loo_torque, weights)
        if got is not None:
            s2.append(got[0] ** 2)
            noise.append(got[1])
            refit.append(parameter_variance(fit, held, weights, solve))
    if not s2:
        return None
    excess = float(np.mean(s2) - np.mean(noise) - np.mean(refit))
    p = fit.model.params
    slope = fit.values.get("u6_slope_m_per_N", p.u6_slope_m_per_N)
    f0 = -fit.values.get("u6_offset_m", p.u6_offset_m) / slope if slope > 0 else None
    distance = force_distance([float(rest[0]), float(rest[-1])], float(edge), f0)
    if distance <= 0.0:
        return None
    from rollaway.uncertainty.predictive import UNSEEN
    floor = math.sqrt(float(np.mean(noise)))
    unseen = UNSEEN * floor if side == "low" else 0.0
    return {"rel_sd": math.sqrt(max(excess, 0.0) + unseen ** 2), "distance": distance, "tests": len(s2),
            "excess_ms": excess, "floor_rel_sd": floor}


def alternatives(selected, competitors: list, keep=(), ties=()) -> list[tuple[float, object]]:
    """Pseudo-BMA weights of *selected* and its competitors (leave-one-test-out scores), heaviest first.
    *keep*: competitors the data cannot tell from *selected* (named beside a verdict): never dropped — not
    for their size, and not for a light weight (floored at :data:`MIN_WEIGHT`).  *selected* keeps at least
    :data:`MIN_WEIGHT` too (it is the saved model: the alternatives' weights add up to less than 1).  *ties*:
    those of *keep* named as rivals (BIC within reach and a held-out difference inside the preference margin):
    each keeps at least its BIC weight among *selected* and the ties (w ∝ exp(−½·BIC), the BIC approximation
    to the posterior probability, Kass & Raftery 1995 §4.1) — with a handful of tests a held-out difference
    inside the margin is noise the Bayesian bootstrap still turns into a light weight, and the sets differ
    most where the bench did not test (the other direction, another force)."""
    kept = {id(c) for c in keep}
    pool = [selected] + [c for c in competitors if c is not selected and c.jacobian is not None
                         and (sized(c) or id(c) in kept)]
    if len(pool) == 1 or selected.jacobian is None:
        return [(1.0, selected)]
    elpd = -0.5 * np.array([loto_scores(f) for f in pool])      # (models, tests) log scores
    rng = np.random.default_rng(0)
    alpha = rng.dirichlet(np.ones(elpd.shape[1]), BOOTSTRAP)                     # Bayesian bootstrap of tests
    z = elpd.shape[1] * alpha @ elpd.T                                           # (BOOTSTRAP, models)
    z -= z.max(axis=1, keepdims=True)
    w = (np.exp(z) / np.exp(z).sum(axis=1, keepdims=True)).mean(axis=0)
    w = w / w.sum()
    tied = [i for i, f in enumerate(pool) if i == 0 or any(f is t for t in ties)]
    if len(tied) > 1:
        b = np.array([pool[i].bic for i in tied])
        wb = np.exp(-0.5 * (b - b.min()))
        w[tied[1:]] = np.maximum(w[tied[1:]], (wb / wb.sum())[1:])
        w = w / w.sum()
    floor = np.array([i == 0 or id(f) in kept for i, f in enumerate(pool)])   # the selected model keeps a share
    w = np.where(floor, np.maximum(w, MIN_WEIGHT), np.where(w >= MIN_WEIGHT, w, 0.0))
    w = w / w.sum()
    out = [(float(wi), f) for wi, f in zip(w, pool) if wi > 0]
    return sorted(out, key=lambda t: -t[0])


def sized(fit) -> bool:
    """True when the data size every effect parameter of *fit* (relative standard error ≤
    :data:`MAX_RELATIVE_SE`, not at a bound) and pin each brake parameter it frees better than that
    parameter's assumed spread: an effect set the data cannot size is no competing explanation — its
    draws would wander through magnitudes (and brake parameters) the data never supported.  The coefficients of
    a shape-free form (:mod:`rollaway.effects.shape_free`) are not sized: its held-out weight judges it."""
    from rollaway.effects.shape_free import is_shape_free
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    shapes = {e.name for e in getattr(getattr(fit, "model", None), "effects", ()) if is_shape_free(e)}
    for name, e in fit.estimates.items():
        if name.split(".")[0] in shapes:     # a spline's coefficients are a shape, not magnitudes to size
            continue
        if "." not in name:        # a brake parameter: the data must pin it better than its assumed spread
            spec = FREE_PARAMETERS.get(name)
            if spec is not None and not (np.isfinite(e.stderr) and e.stderr <= spec.spread(e.value)):
                return False
            continue
        if e.at_bound or not np.isfinite(e.stderr) or e.stderr > MAX_RELATIVE_SE * max(abs(e.value), 1e-300):
            return False
    return True


__all__ = ["alternatives", "edge_error", "model_error", "sized", "start_error", "validity"]
