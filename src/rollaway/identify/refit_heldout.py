"""Held-out residuals that refit the folds where the linearisation fails.

:func:`rollaway.uncertainty.heldout.loto_residuals` linearises leave-one-test-out at the full fit (one
Woodbury step, no refit): exact for a model linear in its parameters, and cheap enough for every candidate
of a selection step.  A flexible form (an effect's hook as a linear spline,
:func:`rollaway.identify.shape.flexible_effect`) on a few tests has directions that one test alone informs;
with that test left out they are nearly singular, and the linear step along them is one no refit would take
(on three tests, a modulus spline's held-out χ² of one test came out 56 500 linearised and 855 refitted).
Where that comparison decides whether an effect is *named* — a second effect against the first re-formed
(:mod:`rollaway.identify.partner`) — each fold's linear step is checked by one model evaluation
(:func:`linear_holds`): the step is kept when it stays within the parameters' bounds and the model there gives
the held-out tests the χ² the linearisation predicts; otherwise the fold is refitted: the globals on the other
tests (started at the full fit, :data:`FOLD_ITERATIONS`, in :data:`FOLD_PASSES` pass), then the held-out tests'
own values (T_0, per-test effect values) on those tests with the globals fixed, as the linearisation profiles
them.
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from rollaway.uncertainty.heldout import folds, linear_step, loto_residuals

HELD_TOLERANCE = 0.1          # a linear step whose held-out χ² the model at that step misses by more is refitted
                              # [assumed: benign folds measured within 0.1–6 %, failed ones 16 % to 60×]
FOLD_ITERATIONS = 2           # a fold's refit budget: FOLD_ITERATIONS·(k + 1) residual calls per pass, from the
                              # full fit [assumed: 1, 2 and 8 gave the same decisions on the campaigns measured]
FOLD_PASSES = 1               # … and at most this many passes between the training tests' T_0 updates (of the
                              # fit's MAX_OUTER): the training tests' T_0 start at the full fit's values [assumed:
                              # the same verdicts on the 816 names campaigns of docs/identification.md, 55–60 % less
                              # time]


def _standardised(data, prediction) -> np.ndarray:
    return np.concatenate([(prediction.drum_temp_C - data.drum_temp_C) / data.temp_sigma_C,
                           (prediction.torque_Nm - data.torque_Nm) / data.torque_sigma_Nm])


def _globals(values: dict) -> dict:
    return {k: v for k, v in values.items() if np.ndim(v) == 0}


def _at(data, model, values: dict):
    """*model*'s standardised residuals on *data* at the global *values*, each test's own values (T_0, per-test
    effect values) fitted on that test."""
    from rollaway.identify.calibrate import calibrate
    return _standardised(data, calibrate(data, model.effects, None, model=model, free=[], start=values,
                                         statistics=False).prediction)


def _fold(data, held, model, names, start, iterations):
    """Standardised residuals [temperature | torque] of the rows of the tests *held*, predicted by *model*
    calibrated (its *names* free, from *start*) on the other tests."""
    from rollaway.identify.calibrate import calibrate
    rows = np.isin(data.test_index, held)
    try:
        train = calibrate(data.subset(~rows), model.effects, None, model=model, free=list(names), start=start,
                          statistics=False, max_iterations=iterations, passes=FOLD_PASSES)
        residual = _at(data.subset(rows), model, _globals(train.values))
    except (ValueError, np.linalg.LinAlgError):     # a fold the solver cannot take (too few residuals left, …)
        residual = None
    if residual is not None and not np.all(np.isfinite(residual)):
        residual = None                 # a refit that ran away (the model there has no finite prediction)
    return SimpleNamespace(data=None, rows=np.concatenate([rows, rows]), residual=residual)


def linear_holds(fit, held) -> bool:
    """True when the linearised leave-out of the tests *held* is trusted: its parameter step stays within the
    bounds, and the model evaluated there (the held-out tests' own values re-profiled) gives those tests the
    held-out χ² the linearisation predicts, within :data:`HELD_TOLERANCE` of it (or of their number of
    residuals, if larger)."""
    g, loo, step = linear_step(fit, held)
    x = np.array([float(fit.values[n]) for n in fit.names]) + step
    bounds = np.array([fit.model.bounds(n) for n in fit.names])
    if not np.all(np.isfinite(x)) or np.any(x < bounds[:, 0]) or np.any(x > bounds[:, 1]):
        return False
    actual = _at(fit.data, fit.model, {**_globals(fit.values), **dict(zip(fit.names, x))})[g]
    linear = float(loo @ loo)
    return abs(float(actual @ actual) - linear) <= HELD_TOLERANCE * max(linear, float(g.sum()))


def _checked_fold(data, fit, held):
    """:func:`_fold` of the tests *held* where their linear step fails :func:`linear_holds`; else no residual (the
    linear step stands).  One job of :func:`refit_loto_residuals`'s batch: the check and, where needed, the
    refit run on the same core."""
    if linear_holds(fit, held):
        return SimpleNamespace(data=None, rows=None, residual=None)
    return _fold(data, held, fit.model, tuple(fit.names), _globals(fit.values), FOLD_ITERATIONS)


def refit_loto_residuals(fits: list, also=()) -> tuple[list[np.ndarray], list[int]]:
    """For each fit of *fits* (all on the same data): its leave-one-test-out standardised residuals
    [temperature | torque] (:func:`rollaway.uncertainty.heldout.loto_residuals`) with every fold whose linear step
    fails :func:`linear_holds` refitted — each fold's check and refit one job, all side by side on the machine's
    cores — and how many folds were refitted (kept on the fit: a fit compared twice is refitted once).  A fold that
    leaves fewer residuals than free globals, or that the solver cannot refit, keeps its linear step; a fit without
    free globals or Jacobian keeps its own residuals.  *also*: more calibrations ``(effects, params, kwargs)`` the
    caller will ask for next, run first in the same batch where there are folds to check (kept for that call by
    :mod:`rollaway.identify.memo`)."""
    from rollaway.identify.workers import run_fits
    data = fits[0].data
    known = [getattr(f, "_refit_heldout", None) for f in fits]     # a fit compared twice is refitted once
    out = [loto_residuals(f) if got is None else got[0].copy() for f, got in zip(fits, known)]
    calls, owner = [], []
    for k, fit in enumerate(fits):
        if fit.jacobian is None or not fit.names or known[k] is not None:
            continue
        for held in folds(data.n_tests):
            left = int(np.count_nonzero(~np.isin(data.test_index, held)))
            if 2 * left > len(fit.names):          # else nothing to refit on: the linear step stands
                calls.append((_checked_fold, (fit, held), {}))
                owner.append(k)
    if calls and also:
        from rollaway.identify.calibrate import calibrate
        ahead = [(calibrate, (effects, params), kw) for effects, params, kw in also]
        done = run_fits(data, ahead + calls)[len(ahead):]
    else:
        done = run_fits(data, calls) if calls else []
    for k, fold in zip(owner, done):
        if fold.residual is not None:
            out[k][fold.rows] = fold.residual
    counts = [known[k][1] if known[k] is not None else
              sum(f.residual is not None for o, f in zip(owner, done) if o == k) for k in range(len(fits))]
    for k, fit in enumerate(fits):
        if known[k] is None:
            fit._refit_heldout = (out[k].copy(), counts[k])
    return out, counts

__all__ = ["FOLD_ITERATIONS", "HELD_TOLERANCE", "linear_holds", "refit_loto_residuals"]
