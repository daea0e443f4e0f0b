"""Is the 90 % band 90 % on *your* bench?  A calibration self-check on the user's own test design.

:func:`check_calibration` makes N synthetic campaigns that look like the user's: the same tests
(hand forces, directions, sampling times), each from a "truth" drawn from the calibrated
model's predictive distribution (a parameter draw, its competing effect sets by weight, a
model error ε), plus the measured residuals resampled test by test (a block bootstrap: each
synthetic test takes the whole residual series of a real test, so their autocorrelation and
per-test structure travel with them).  Each campaign is diagnosed as the user's was (``diag.again``: the
diagnosis knows how it was made, so this module needs nothing of :mod:`rollaway.identify`), its model
answers the design question (facing uphill, the tested mid hand force, T_0 200 °C, one hour,
on the grade where the truth's least margin is 1), and the check counts how often the 5–95 %
band of the least margin holds the truth.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from rollaway.errors import UserError

CASE = {"direction": "uphill", "occupants": 1, "duration_s": 3600.0, "initial_temp_C": 200.0}


def _truth_margin(model, force_N: float, grade_pct: float) -> float:
    from rollaway.hold import min_brake_margin
    return float(min_brake_margin(model, force_N, grade_pct, CASE["direction"], CASE["occupants"],
                                  CASE["duration_s"], initial_temp_C=CASE["initial_temp_C"]))


def _grade_for_margin(model, force_N: float, target: float = 1.0) -> float:
    from scipy.optimize import brentq
    f = lambda g: _truth_margin(model, force_N, g) - target  # noqa: E731
    lo, hi = 0.5, 100.0
    if f(lo) < 0 or f(hi) > 0:
        return 20.0
    return float(brentq(f, lo, hi, xtol=1e-3))


def check_calibration(diag, n: int, *, draws: int = 300, seed: int = 0) -> dict:
    """Coverage of the 5–95 % least-margin band over *n* synthetic campaigns of the user's design."""
    from rollaway.uncertainty.draws import draw_values, own_record, rollaway_risk
    from rollaway.uncertainty.predictive import model_error_draws

    if not (isinstance(n, (int, np.integer)) and 1 <= n <= 1000):
        raise UserError(f"--check-calibration {n} must be a whole number of campaigns from 1 to 1000, e.g. 20")
    model = diag.model
    data = diag.data
    rng = np.random.default_rng(seed)
    rt, rq = diag.refined.residuals()
    force = float(np.median(np.unique(data.hand_force_N)))
    covered, widths, results = 0, [], []
    for k in range(n):
        parts = [(1.0 - sum(w for w, _ in model.alternatives), model)] + list(model.alternatives)
        truth = parts[rng.choice(len(parts), p=np.array([w for w, _ in parts]))][1]
        own = own_record(model.predictive, truth)
        if truth.covariance is not None:
            truth = truth.with_draw({a: float(b[0]) for a, b in draw_values(truth, 1, int(rng.integers(2**31))).items()})
        eps = float(model_error_draws(own, 1, 1.0, rng)[0])
        series = truth.evaluate(data.time_s, data.hand_force_N, data.sign, initial_temp_C=data.initial_temp_C,
                                ambient_C=data.ambient_C)
        donors = rng.integers(data.n_tests, size=data.n_tests)       # block bootstrap of whole-test residuals
        noise_t, noise_q = np.zeros(len(data)), np.zeros(len(data))
        for i, j in enumerate(donors):
            rows, src = np.flatnonzero(data.test_index == i), np.flatnonzero(data.test_index == j)
            take = src[np.arange(rows.size) % src.size]
            noise_t[rows], noise_q[rows] = rt[take], rq[take]
        synth = dataclasses.replace(data, drum_temp_C=series.drum_temp_C + noise_t,
                                    torque_Nm=series.torque_Nm * (1.0 + eps) + noise_q,
                                    torque_sigma_Nm=None, temp_sigma_C=None, source=f"calibration check {k + 1}")
        grade = _grade_for_margin(truth, force)
        true_margin = _truth_margin(truth, force, grade) * (1.0 + eps)
        fitted = diag.again(synth).model
        risk = rollaway_risk(fitted, hand_force_N=force, grade_pct=grade, draws=draws, seed=k, **CASE)
        p = risk.brake_margin_percentiles
        hit = p["p5"] <= true_margin <= p["p95"]
        covered += hit
        widths.append(0.5 * (p["p95"] - p["p5"]))
        results.append({"truth": true_margin, "p5": p["p5"], "p95": p["p95"], "covered": bool(hit)})
    return {"campaigns": n, "coverage": covered / n, "median_half_width": float(np.median(widths)),
            "question": {**CASE, "hand_force_N": force}, "results": results}


def words(check: dict) -> str:
    c = check["coverage"]
    verdict = ("as it should" if c >= 0.8 else "LOWER than it says: widen your margins or test more")
    return (f"calibration check: the 5–95 % band held the truth in {c:.0%} of {check['campaigns']} synthetic "
            f"campaigns of your test design (nominal 90 %; {verdict}); median half-width "
            f"{check['median_half_width']:.3g} of margin")


__all__ = ["check_calibration", "words"]
