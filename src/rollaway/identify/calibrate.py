"""Calibration: least-squares fit of the bench model's free parameters (lmfit-style result).

The drum-temperature channel does not depend on torque parameters, so the fit is done in
two exact stages: (1) h plus temperature-changing effects against the drum temperature
(samples after t = 0; T_0 is taken from the data), (2) μ_d plus the other effect parameters
against the torque, with the stage-1 temperatures.  Each stage's covariance comes from its
Jacobian: ``cov = s²·(JᵀJ)⁻¹``, 95 % intervals with Student's t.  The information criteria
add both channels' Gaussian log-likelihoods (each with its own variance):
``BIC = Σ_c n_c·ln(RSS_c/n_c) + k·ln(N)``, ``AIC = … + 2k``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize, stats

from rollaway.identify.measurements import Measurements
from rollaway.identify.model import BenchModel, Prediction


@dataclass
class ParameterEstimate:
    name: str
    value: float
    unit: str
    stderr: float
    ci95: tuple[float, float]
    lower: float
    upper: float
    at_bound: str = ""          # "", "lower" or "upper"

    def as_dict(self) -> dict:
        return {"value": self.value, "unit": self.unit, "stderr": self.stderr, "ci95": list(self.ci95),
                "bounds": [self.lower, self.upper], "at_bound": self.at_bound or None}


@dataclass
class FitResult:
    """The calibrated model: values, intervals, errors per channel and information criteria."""

    model: BenchModel
    data: Measurements
    values: dict[str, float]
    estimates: dict[str, ParameterEstimate]
    prediction: Prediction
    rss_temp: float
    rss_torque: float
    n_temp: int
    n_torque: int
    warnings: list[str] = field(default_factory=list)
    rss_torque_weighted: float | None = None   # the WLS objective (= rss_torque without a noise model)
    fit_info: dict = field(default_factory=dict)   # per stage: initial values, evaluations, convergence, correlation

    @property
    def effects(self) -> list[str]:
        return [e.name for e in self.model.effects]

    @property
    def k(self) -> int:
        return len(self.estimates)

    @property
    def rmse_temp_C(self) -> float:
        return math.sqrt(self.rss_temp / max(self.n_temp, 1))

    @property
    def rmse_torque_Nm(self) -> float:
        return math.sqrt(self.rss_torque / max(self.n_torque, 1))

    def _loglik_term(self) -> float:
        tiny = 1e-12
        rss_q = self.rss_torque if self.rss_torque_weighted is None else self.rss_torque_weighted
        return (self.n_temp * math.log(max(self.rss_temp / max(self.n_temp, 1), tiny))
                + self.n_torque * math.log(max(rss_q / max(self.n_torque, 1), tiny)))

    @property
    def bic(self) -> float:
        return self._loglik_term() + self.k * math.log(self.n_temp + self.n_torque)

    @property
    def aic(self) -> float:
        return self._loglik_term() + 2 * self.k

    def residuals(self) -> tuple[np.ndarray, np.ndarray]:
        """Measured − model: (drum temperature [°C], torque [N·m])."""
        return (self.data.drum_temp_C - self.prediction.drum_temp_C, self.data.torque_Nm - self.prediction.torque_Nm)

    def effect_parameters(self, effect: str) -> dict[str, dict]:
        return {n.split(".", 1)[1]: e.as_dict() for n, e in self.estimates.items() if n.startswith(effect + ".")}

    def report(self) -> str:
        """lmfit-style text report."""
        lines = [f"model: baseline{''.join(' + ' + e for e in self.effects)}  ({len(self.data)} samples, "
                 f"{self.data.n_tests} tests)",
                 f"  RMSE torque {self.rmse_torque_Nm:.3g} N·m, drum temperature {self.rmse_temp_C:.3g} °C; "
                 f"AIC {self.aic:.1f}, BIC {self.bic:.1f}, k = {self.k}"]
        for e in self.estimates.values():
            flag = f"   AT {e.at_bound.upper()} BOUND" if e.at_bound else ""
            lines.append(f"  {e.name:<45} {e.value:>12.5g} ± {e.stderr:<10.3g} [{e.ci95[0]:.4g}, {e.ci95[1]:.4g}] "
                         f"{e.unit}{flag}")
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines)

    def __repr__(self) -> str:
        return self.report()

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import fit_html
        return fit_html(self)


def _stage(model: BenchModel, names: list[str], fixed: dict, start: dict, residual_fn, info: dict | None = None):
    """One least-squares stage over *names*; returns values, stderr, rss, n.

    *info* (a dict) receives the fit diagnostics: initial values, number of evaluations,
    convergence status and message, and the parameters' correlation matrix.
    """
    if not names:
        r = residual_fn(dict(fixed))
        return {}, {}, float(r @ r), r.size
    lo = np.array([model.bounds(n)[0] for n in names])
    hi = np.array([model.bounds(n)[1] for n in names])
    x0 = np.clip(np.array([start[n] for n in names], float), lo, hi)
    x0 = np.where(x0 <= lo, lo + 1e-6 * (hi - lo), np.where(x0 >= hi, hi - 1e-6 * (hi - lo), x0))
    scale = np.maximum(np.abs(x0), 1e-3 * (hi - lo))

    def fun(z):
        vals = dict(fixed)
        vals.update(zip(names, z * scale))
        return residual_fn(vals)

    res = optimize.least_squares(fun, x0 / scale, bounds=(lo / scale, hi / scale), method="trf",
                                 x_scale=1.0, xtol=1e-10, ftol=1e-10, gtol=1e-10, max_nfev=200 * len(names))
    x = res.x * scale
    r = res.fun
    rss, n = float(r @ r), r.size
    jac = res.jac / scale
    dof = max(n - len(names), 1)
    try:
        cov = np.linalg.pinv(jac.T @ jac) * rss / dof
        se = np.sqrt(np.clip(np.diag(cov), 0, None))
    except np.linalg.LinAlgError:
        cov, se = None, np.full(len(names), np.nan)
    if info is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            corr = None if cov is None else cov / np.outer(se, se)
        info.update(names=list(names), initial=dict(zip(names, (x0 * 1.0).tolist())), nfev=int(res.nfev),
                    success=bool(res.success), status=int(res.status), message=str(res.message),
                    n=int(n), rss=rss, correlation=None if corr is None else corr.tolist())
    return dict(zip(names, x)), dict(zip(names, se)), rss, n


def calibrate(data: Measurements, effects=(), params=None, *, free=None, start: dict | None = None,
              model: BenchModel | None = None) -> FitResult:
    """Fit μ_d, h and every parameter of *effects* to *data*; return a :class:`FitResult`.

    *free* restricts the fitted names (others stay at *start*/neutral); *start* gives
    starting values (defaults: the set's μ_d and h, each effect parameter's ``initial``).
    """
    model = model or BenchModel(params, effects)
    values = model.neutral_values()
    init = dict(values)
    for e in model.effects:
        init.update({f"{e.name}.{p.name}": p.initial for p in e.parameters})
    init.update(start or {})
    free = set(model.parameter_names() if free is None else free)
    temp_names = [n for n in model.temperature_parameters() if n in free]
    torque_names = [n for n in model.torque_parameters() if n in free]
    fixed = {n: init[n] if n in free else (start or {}).get(n, values[n]) for n in model.parameter_names()}
    hot = data.time_s > 0

    def temp_res(vals):
        return (model.drum_temperature(data, vals) - data.drum_temp_C)[hot]

    info_t, info_q = {"channel": "temperature"}, {"channel": "torque"}
    tv, tse, rss_t, n_t = _stage(model, temp_names, fixed, init, temp_res, info_t)
    fixed.update(tv)
    temp = model.drum_temperature(data, fixed)

    w = 1.0 if data.torque_sigma_Nm is None else np.mean(data.torque_sigma_Nm) / data.torque_sigma_Nm

    def torque_res(vals):   # weighted by 1/σ_i when a noise model is attached (WLS)
        return (model.predict(data, vals, drum_temp_C=temp).torque_Nm - data.torque_Nm) * w

    qv, qse, rss_q, n_q = _stage(model, torque_names, fixed, init, torque_res, info_q)
    fixed.update(qv)
    pred = model.predict(data, fixed, drum_temp_C=temp)
    estimates, warnings = {}, []
    for names, se, n in ((temp_names, tse, n_t), (torque_names, qse, n_q)):
        tcrit = stats.t.ppf(0.975, max(n - len(names), 1))
        for name in names:
            lo, hi = model.bounds(name)
            v = fixed[name]
            tol = 1e-4 * (hi - lo)
            at = "lower" if v - lo <= tol else "upper" if hi - v <= tol else ""
            s = float(se[name])
            estimates[name] = ParameterEstimate(name, float(v), model.unit(name), s,
                                                (float(v - tcrit * s), float(v + tcrit * s)), lo, hi, at)
            if at:
                warnings.append(f"{name} = {v:.4g} is stuck at its {at} bound "
                                f"({lo if at == 'lower' else hi:g} {model.unit(name)}); the data push it out of "
                                f"the physical range or the effect is absent — its interval is not meaningful")
    rq = data.torque_Nm - pred.torque_Nm
    return FitResult(model, data, fixed, estimates, pred, rss_t, float(rq @ rq), n_t, n_q, warnings, rss_q,
                     {"stages": [i for i in (info_t, info_q) if "names" in i]})


def evaluate(data: Measurements, effects=(), params=None, values: dict | None = None) -> FitResult:
    """The model at given values (no fitting), wrapped as a FitResult (k = 0)."""
    model = BenchModel(params, effects)
    vals = {**model.neutral_values(), **(values or {})}
    pred = model.predict(data, vals)
    hot = data.time_s > 0
    rt = (data.drum_temp_C - pred.drum_temp_C)[hot]
    rq = data.torque_Nm - pred.torque_Nm
    w = 1.0 if data.torque_sigma_Nm is None else np.mean(data.torque_sigma_Nm) / data.torque_sigma_Nm
    return FitResult(model, data, vals, {}, pred, float(rt @ rt), float(rq @ rq), int(hot.sum()), rq.size, [],
                     float(((rq * w) ** 2).sum()))
