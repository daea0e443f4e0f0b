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


def loto_residuals(fit) -> np.ndarray:
    """Standardised residuals (model − measured)/σ, [temperature | torque], of every sample as
    predicted with its own test (its fold) left out of the calibration: the linearised
    leave-one-test-out of :func:`cv_score`.  Without a Jacobian: the fit's own residuals."""
    d = fit.data
    pred = fit.prediction
    r = np.concatenate([(pred.drum_temp_C - d.drum_temp_C) / d.temp_sigma_C,
                        (pred.torque_Nm - d.torque_Nm) / d.torque_sigma_Nm])
    if fit.jacobian is None or not fit.names:
        return r
    j = np.where(np.isfinite(fit.jacobian), fit.jacobian, 0.0)
    j = j / np.sqrt(np.maximum((j * j).sum(axis=0), 1e-300))
    rows_test = np.concatenate([d.test_index, d.test_index])
    a = j.T @ j
    out = r.copy()
    for held in folds(d.n_tests):
        g = np.isin(rows_test, held)
        jg, rg = j[g], r[g]
        m = a - jg.T @ jg
        m += 1e-10 * np.trace(m) / max(len(m), 1) * np.eye(len(m))
        out[g] = rg + jg @ np.linalg.lstsq(m, jg.T @ rg, rcond=1e-8)[0]   # a direction only g informs: dropped
    return out


def loto_scores(fit) -> np.ndarray:
    """Per test, Σ (held-out residual/σ)² of both channels (:func:`loto_residuals`)."""
    d = fit.data
    loto = loto_residuals(fit)
    return np.bincount(np.concatenate([d.test_index, d.test_index]), loto * loto, d.n_tests)


__all__ = ["FOLDS", "LOO_TESTS", "folds", "loto_residuals", "loto_scores"]
