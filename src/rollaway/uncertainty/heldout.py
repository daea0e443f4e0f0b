"""Held-out prediction errors: every test predicted by the model calibrated on the other tests.

The effect selection scores candidates with them (:func:`rollaway.identify.selection.cv_score`)
and the predictive bands measure the model error from them (:mod:`rollaway.uncertainty.bands`).
Linearised at the full fit (no refit): with J the column-normalised Jacobian and r the
standardised residual, leaving out the rows g of a fold moves the parameters by
(JᵀJ − J_gᵀJ_g)⁻¹·J_gᵀ·r_g (Woodbury; exact for a model linear in its parameters).

A *fit* here is any object with ``data`` (measurements with ``test_index``, ``n_tests``,
``drum_temp_C``, ``torque_Nm`` and their sigmas), ``prediction`` (``drum_temp_C``,
``torque_Nm``), ``jacobian`` (or None) and ``names`` (the free parameters).
"""
from __future__ import annotations

import numpy as np

LOO_TESTS = 10               # K-fold by test: leave-one-test-out up to 10 tests, else FOLDS folds
FOLDS = 5


def folds(n_tests: int) -> list[np.ndarray]:
    """Test indices of each held-out fold: one test each up to LOO_TESTS tests, else FOLDS folds."""
    k = n_tests if n_tests <= LOO_TESTS else FOLDS
    return [np.arange(i, n_tests, k) for i in range(k)]


def _normalised_jacobian(fit):
    j = np.where(np.isfinite(fit.jacobian), fit.jacobian, 0.0)
    return j / np.sqrt(np.maximum((j * j).sum(axis=0), 1e-300))


def _fold_solver(a: np.ndarray, jg: np.ndarray):
    """x ↦ (JᵀJ − J_gᵀJ_g)⁺·x for the rows g of one fold (directions only g informs dropped)."""
    m = a - jg.T @ jg
    m += 1e-10 * np.trace(m) / max(len(m), 1) * np.eye(len(m))
    return lambda x: np.linalg.lstsq(m, x, rcond=1e-8)[0]


def _standardised(fit) -> np.ndarray:
    d, pred = fit.data, fit.prediction
    return np.concatenate([(pred.drum_temp_C - d.drum_temp_C) / d.temp_sigma_C,
                           (pred.torque_Nm - d.torque_Nm) / d.torque_sigma_Nm])


def held_out(fit, held) -> tuple[np.ndarray, np.ndarray, object]:
    """(rows g of [temperature | torque] that belong to the tests *held*, their standardised residuals predicted
    with all of those tests left out of the calibration, and x ↦ (JᵀJ − J_gᵀJ_g)⁺·x in the normalised
    Jacobian's units).  Needs a Jacobian."""
    d = fit.data
    j = _normalised_jacobian(fit)
    r = _standardised(fit)
    g = np.isin(np.concatenate([d.test_index, d.test_index]), held)
    jg, rg = j[g], r[g]
    solve = _fold_solver(j.T @ j, jg)
    return g, rg + jg @ solve(jg.T @ rg), solve


def linear_step(fit, held) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rows g of [temperature | torque] of the tests *held*, their linearised held-out standardised residuals, and
    the step of the free parameters (``fit.names``, in their own units) that leaving those tests out takes in the
    linearisation: Δθ = (JᵀJ − J_gᵀJ_g)⁺·J_gᵀ·r_g).  Needs a Jacobian."""
    d = fit.data
    j = np.where(np.isfinite(fit.jacobian), fit.jacobian, 0.0)
    norms = np.sqrt(np.maximum((j * j).sum(axis=0), 1e-300))
    g, loo, solve = held_out(fit, held)
    jg = j[g] / norms
    return g, loo, solve(jg.T @ _standardised(fit)[g]) / norms


def loto_residuals(fit) -> np.ndarray:
    """Standardised residuals (model − measured)/σ, [temperature | torque], of every sample as
    predicted with its own test (its fold) left out of the calibration: the linearised
    leave-one-test-out of :func:`cv_score`.  Without a Jacobian: the fit's own residuals."""
    out = _standardised(fit)
    if fit.jacobian is None or not fit.names:
        return out
    for held in folds(fit.data.n_tests):
        g, loo, _ = held_out(fit, held)
        out[g] = loo
    return out


def parameter_variance(fit, held, weights: np.ndarray, solve=None) -> float:
    """The variance that re-calibrating without the tests *held* adds to Σ_i w_i·r_i of their held-out standardised
    residuals when the model is right: wᵀ·J·(JᵀJ − J_gᵀJ_g)⁺·Jᵀ·w (*weights*: one per row of [temperature | torque],
    zero outside the rows scored; *solve*: :func:`held_out`'s, when at hand)."""
    j = _normalised_jacobian(fit)
    if solve is None:
        solve = held_out(fit, held)[2]
    v = j.T @ np.asarray(weights, float)
    return float(v @ solve(v))


def loto_parameter_variance(fit, weights: np.ndarray) -> np.ndarray:
    """Per test k, :func:`parameter_variance` of k's fold for the weights on k's rows (the held-out residual's
    covariance is (I − H_gg)⁻¹ = I + J_g·(JᵀJ − J_gᵀJ_g)⁻¹·J_gᵀ; the identity part is the noise)."""
    d = fit.data
    out = np.zeros(d.n_tests)
    if fit.jacobian is None or not fit.names:
        return out
    w = np.asarray(weights, float)
    rows_test = np.concatenate([d.test_index, d.test_index])
    for held in folds(d.n_tests):
        solve = held_out(fit, held)[2]
        for k in held:
            out[k] = parameter_variance(fit, held, np.where(rows_test == k, w, 0.0), solve)
    return out


def loto_scores(fit) -> np.ndarray:
    """Per test, Σ (held-out residual/σ)² of both channels (:func:`loto_residuals`)."""
    d = fit.data
    loto = loto_residuals(fit)
    return np.bincount(np.concatenate([d.test_index, d.test_index]), loto * loto, d.n_tests)


__all__ = ["FOLDS", "LOO_TESTS", "folds", "held_out", "linear_step", "loto_parameter_variance", "loto_residuals",
           "loto_scores", "parameter_variance"]
