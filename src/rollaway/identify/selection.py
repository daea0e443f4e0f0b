"""Model selection for :mod:`rollaway.identify.diagnose`: residual structure, K-fold cross-validation
by test, and the forward, exchange and backward-elimination steps over candidate effects.

Every candidate is a calibrated :class:`~rollaway.identify.calibrate.FitResult` of the drum
model with some effects; ΔBIC ranks them, cross-validation (each held-out test predicted by a
model calibrated on the other tests) guards against effects that only fit noise.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.identify.calibrate import FitResult, calibrate
from rollaway.identify.measurements import Measurements
from rollaway.identify.noise import Noise
from rollaway.identify.residuals import structure_tests

BIC_THRESHOLD = -10.0        # "very strong" evidence (Kass & Raftery 1995)
CV_TOP = 3                   # cross-validate at most this many candidates per step
LOO_TESTS = 10               # K-fold by test: leave-one-test-out up to 10 tests, else FOLDS folds
FOLDS = 5


@dataclass
class Candidate:
    effect: str
    fit: FitResult
    delta_bic: float
    delta_aic: float
    cv_score: float | None = None       # Σ over held-out tests of Σ (residual/σ)², both channels
    cv_better_tests: int | None = None
    step: int = 1                       # forward-selection step in which it was tried

    def as_dict(self) -> dict:
        return {"effect": self.effect, "rmse_torque_Nm": self.fit.rmse_torque_Nm, "rmse_temp_C": self.fit.rmse_temp_C,
                "delta_bic": self.delta_bic, "delta_aic": self.delta_aic, "bic": self.fit.bic,
                "cv_score": self.cv_score, "cv_better_tests": self.cv_better_tests, "step": self.step,
                "parameters": self.fit.effect_parameters(self.effect), "warnings": self.fit.warnings}


# -- structure ------------------------------------------------------------------------------
def structure(fit: FitResult, nq: Noise, nt: Noise) -> dict:
    rt, rq = fit.residuals()
    kq = fit.effective_parameters.get("torque", len(fit.model.torque_parameters()))
    kt = fit.effective_parameters.get("temperature", len(fit.model.temperature_parameters()))
    out = {"torque": structure_tests(fit.data, rq, nq, kq, sigma=fit.data.torque_sigma_Nm),
           "temperature": structure_tests(fit.data, rt, nt, kt, sigma=fit.data.temp_sigma_C)}
    out["structured"] = out["torque"]["structured"] or out["temperature"]["structured"]
    return out


def weighted_chi2(fit: FitResult) -> float:
    return float((fit.rss_torque_weighted or 0.0) + (fit.rss_temp_weighted or 0.0))


# -- cross-validation -----------------------------------------------------------------------
def folds(n_tests: int) -> list[np.ndarray]:
    """Test indices of each held-out fold: one test each up to LOO_TESTS tests, else FOLDS folds."""
    k = n_tests if n_tests <= LOO_TESTS else FOLDS
    return [np.arange(i, n_tests, k) for i in range(k)]


def _restrict(values: dict, families: list[str], keep: np.ndarray) -> dict:
    out = dict(values)
    for f in families:
        if f in out and np.ndim(out[f]) == 1:
            out[f] = np.asarray(out[f])[keep]
    return out


def cv_score(data: Measurements, effects, params, start: FitResult) -> np.ndarray:
    """K-fold by test: per held-out test, Σ (residual/σ)² of both channels under a model calibrated
    on the other folds (warm-started at *start*); only the held-out test's own T_0 and per-test
    values are fitted to it."""
    scores = np.zeros(data.n_tests)
    fams = start.model.per_test_parameters()
    glob = start.model.parameter_names()
    for held in folds(data.n_tests):
        out = np.isin(data.test_index, held)
        keep = np.setdiff1d(np.arange(data.n_tests), held)
        train, test = data.subset(~out), data.subset(out)
        fit = calibrate(train, effects, params, start=_restrict(start.values, fams, keep), statistics=False)
        vals = {n: fit.values[n] for n in glob}
        vals.update(_restrict(start.values, fams, np.asarray(held)))
        pred = calibrate(test, effects, params, free=[], start=vals, statistics=False)
        r = np.concatenate([(test.drum_temp_C - pred.prediction.drum_temp_C) / test.temp_sigma_C,
                            (test.torque_Nm - pred.prediction.torque_Nm) / test.torque_sigma_Nm])
        scores[np.asarray(held)] = np.bincount(np.concatenate([test.test_index, test.test_index]), r * r,
                                               test.n_tests)
    return scores


# -- the steps ---------------------------------------------------------------------------
def forward_step(data, params, names, current: FitResult, chosen: list[str], step: int):
    """Fit every remaining candidate on top of *current*; cross-validate the strong ones."""
    start = {k: v for k, v in current.values.items()}
    cands = []
    for name in names:
        if name in chosen:
            continue
        fit = calibrate(data, chosen + [name], params, start=start)
        cands.append(Candidate(name, fit, fit.bic - current.bic, fit.aic - current.aic, step=step))
    cands.sort(key=lambda c: c.delta_bic)
    strong = [c for c in cands if c.delta_bic < BIC_THRESHOLD][:CV_TOP]
    cur_cv = None
    if strong:
        cur_scores = cv_score(data, chosen, params, current)
        cur_cv = float(cur_scores.sum())
        for c in strong:
            s = cv_score(data, chosen + [c.effect], params, c.fit)
            c.cv_score = float(s.sum())
            c.cv_better_tests = int((s < cur_scores).sum())
    passing = [c for c in strong if c.cv_score is not None and c.cv_score < cur_cv]
    return cands, strong, passing, cur_cv


def exchange(data, params, names, chosen, current, struct, nq, nt, rounds: int = 2):
    """Stepwise exchange: replace a selected effect by an unselected one while BIC improves and the
    residual stays as clean (forward selection can pick an effect that absorbs part of a later one)."""
    swaps = []
    for _ in range(rounds):
        best = None
        for i, old in enumerate(chosen):
            for new in names:
                if new in chosen:
                    continue
                trial = chosen[:i] + [new] + chosen[i + 1:]
                fit = calibrate(data, trial, params, start=current.values, statistics=False)
                if fit.bic < current.bic - 2.0 and (best is None or fit.bic < best[2].bic):
                    best = (i, new, fit)
        if best is None:
            break
        i, new, _ = best
        trial = chosen[:i] + [new] + chosen[i + 1:]
        fit = calibrate(data, trial, params, start=best[2].values)
        s = structure(fit, nq, nt)
        if s["structured"] and not struct["structured"]:
            break
        swaps.append((chosen[i], new, fit.bic - current.bic))
        chosen, current, struct = trial, fit, s
    return chosen, current, struct, swaps


def eliminate(data, params, chosen, current, struct, nq, nt):
    """Backward elimination: drop a selected effect when the model without it has the lower BIC and a
    residual as clean."""
    removed = []
    while len(chosen) >= 2:
        trials = []
        for i in range(len(chosen)):
            rest = chosen[:i] + chosen[i + 1:]
            trials.append((calibrate(data, rest, params, start=current.values), i))
        fit, i = min(trials, key=lambda t: t[0].bic)
        if fit.bic >= current.bic:
            break
        s = structure(fit, nq, nt)
        if s["structured"] and not struct["structured"]:
            break
        removed.append((chosen[i], fit.bic - current.bic))
        chosen, current, struct = chosen[:i] + chosen[i + 1:], fit, s
    return chosen, current, struct, removed
