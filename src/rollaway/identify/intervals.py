"""Parameter intervals that count what a least-squares covariance leaves out.

A fit's own covariance (:func:`rollaway.identify.calibrate.calibrate`) treats the residuals as
independent and the model as given.  Three things make such 95 % intervals too narrow on bench data:

1. **Autocorrelated residuals.**  Window means of a dense log, and a model form that is slightly
   off, leave residuals that follow each other within a test.  With lag-1 autocorrelation ρ of the
   standardised residual (consecutive samples of the same test), an AR(1) series of n samples holds
   the information of n·(1 − ρ)/(1 + ρ) independent ones (the effective sample size; Bayley &
   Hammersley 1946, "The effective number of independent observations in an autocorrelated time
   series", J. R. Stat. Soc. Suppl. 8; Zwiers & von Storch 1995, J. Climate 8, eq. 3).  Each
   channel's variance factor is multiplied by (1 + ρ)/(1 − ρ) (ρ > 0 only, capped at
   :data:`MAX_RHO`): :func:`ess_inflation`.
2. **Parameters held at their assumed values.**  A brake parameter fixed because the data agree
   with its assumed value (or cannot see it) is not known exactly: its assumed spread enters as a
   Gaussian prior and the fitted parameters' covariance is the marginal one
   (:func:`rollaway.identify.drum.predictive_covariance`), i.e. averaged over the fixed parameters
   instead of conditioned on them.  The installation gap ``gap_m`` is one of them, always: no torque log
   tells it from μ_d (:mod:`rollaway.model.drum_parameters`); the bands then draw conditional on it.
3. **The choice of effects.**  When competing effect sets carry weight (pseudo-BMA,
   :func:`rollaway.uncertainty.bands.alternatives`), a parameter's variance is that of the mixture:
   Σ wᵢ·(varᵢ + (mᵢ − m)²) with m the reported value (Hoeting et al. 1999, "Bayesian model
   averaging: a tutorial", Stat. Sci. 14, eq. 2 with the selected model's value as the centre).

:func:`restate` writes the result back into the fit's estimates (stderr and ci95, Student-t
quantile as before); the fit's covariance becomes the one the bands draw from.
"""
from __future__ import annotations

import math

import numpy as np

from rollaway.scipy_direct import special_functions

special = special_functions()      # scipy.special's ufuncs without its package start (rollaway.scipy_direct)

MAX_RHO = 0.95               # (1 + ρ)/(1 − ρ) ≤ 39: a residual that is one smooth curve is a misfit, not noise


def lag1(fit, channel: str) -> float:
    """Lag-1 autocorrelation of the standardised residual of *channel* over consecutive samples of each test."""
    d = fit.data
    rt, rq = fit.residuals()
    n = len(rq)
    r = (rq / d.torque_sigma_Nm) if channel == "torque" else (rt / d.temp_sigma_C)
    r = np.asarray(r, float)
    mean = np.bincount(d.test_index, r, d.n_tests) / np.maximum(np.bincount(d.test_index, None, d.n_tests), 1)
    r = r - mean[d.test_index]
    order = np.lexsort((d.time_s, d.test_index))
    r, tid = r[order], d.test_index[order]
    same = tid[1:] == tid[:-1]
    if n < 3 or not same.any():
        return 0.0
    den = float(r @ r)
    return float(np.sum(r[1:][same] * r[:-1][same]) / den) if den > 0 else 0.0


def ess_inflation(fit) -> dict[str, float]:
    """Per channel, the variance inflation (1 + ρ)/(1 − ρ) of lag-1 autocorrelated residuals (≥ 1)."""
    out = {}
    for ch in ("temperature", "torque"):
        rho = min(max(lag1(fit, ch), 0.0), MAX_RHO)
        out[ch] = (1.0 + rho) / (1.0 - rho)
    return out


def mixture_variances(fit, alternatives) -> dict[str, float]:
    """Total variance of each of *fit*'s parameters over the mixture of *fit* (weight 1 − Σ w) and its weighted
    *alternatives* ((weight, fit) pairs): Σ wᵢ·(varᵢ + (mᵢ − m)²), m = *fit*'s value.  An alternative without
    the parameter contributes *fit*'s own variance.  Empty when there are no alternatives."""
    cov = getattr(fit, "covariance", None)
    out = {}
    if not alternatives or cov is None:
        return out
    w0 = 1.0 - sum(w for w, _ in alternatives)
    for name in cov.names:
        if name not in fit.values or np.ndim(fit.values[name]):
            continue
        m = float(fit.values[name])
        total = w0 * _var(cov, name)
        for w, f in alternatives:
            c = getattr(f, "covariance", None)
            if name not in f.values or c is None or name not in c.names:
                total += w * _var(cov, name)
                continue
            total += w * (_var(c, name) + (float(f.values[name]) - m) ** 2)
        out[name] = total
    return out


def _var(cov, name: str) -> float:
    i = cov.names.index(name)
    return float(cov.matrix[i, i])


def restate(fit, variances: dict[str, float]) -> None:
    """Write standard errors and 95 % intervals of *fit*'s estimates from *variances* (name → variance)."""
    n = len(fit.data)
    p = sum(fit.effective_parameters.values()) if fit.effective_parameters else len(fit.names)
    tcrit = special.stdtrit(max(2 * n - p, 1), 0.975)
    for name, var in variances.items():
        e = fit.estimates.get(name)
        if e is None or not np.isfinite(var) or var < 0:
            continue
        s = math.sqrt(var)
        if np.isfinite(e.stderr) and s < e.stderr:
            s = e.stderr                  # never narrower than the fit's own interval
        e.stderr = s
        e.ci95 = (max(e.lower, e.value - tcrit * s), min(e.upper, e.value + tcrit * s))


def covariance_variances(fit) -> dict[str, float]:
    """name → variance from the fit's (marginal, inflated) covariance."""
    cov = getattr(fit, "covariance", None)
    if cov is None:
        return {}
    return {n: _var(cov, n) for n in cov.names if n in fit.estimates}


__all__ = ["MAX_RHO", "covariance_variances", "ess_inflation", "lag1", "mixture_variances", "restate"]
