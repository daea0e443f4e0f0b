"""Calibration: one joint fit of both channels (lmfit-style result).

Both measured channels are fitted together, each sample standardised by its noise σ
(a model-free estimate, :mod:`rollaway.bench.noise`, or the instrument's figure), with
every test's start temperature T_0 a nuisance parameter (the t = 0 reading is one noisy
measurement of it, not its value) and per-test effect parameters profiled out
(:mod:`rollaway.identify.fitting`).

Covariance: ``cov = (J̃ᵀJ̃)⁻¹`` of the projected Jacobian in scaled variables, each channel's
rows divided by √φ_c, φ_c = Σ(r/σ)²/(n_c − p_c) its residual variance factor (p_c: the
channel's summed leverages), so a wrong σ does not shrink or inflate the intervals.  95 %
intervals use Student's t and are clipped to the physical bounds; directions the data do
not determine get an infinite error.  The information criteria add both channels' Gaussian
log-likelihoods (each with its own variance): ``BIC = Σ_c n_c·ln(RSS_c/n_c) + k·ln(N)``,
``AIC = … + 2k``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rollaway.bench.measurements import Measurements
from rollaway.identify.fitting import Problem, single_blas_thread
from rollaway.identify.model import INITIAL_TEMP, BenchModel, Prediction
from rollaway.scipy_direct import special_functions

special = special_functions()      # scipy.special's ufuncs without its package start (rollaway.scipy_direct)


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
    rss_torque_weighted: float | None = None   # Σ (residual/σ)² of the torque channel
    rss_temp_weighted: float | None = None     # Σ (residual/σ)² of the temperature channel
    per_test: dict = field(default_factory=dict)    # family → {"values", "stderr", "unit"} (one per test)
    correlation: np.ndarray | None = None      # correlation matrix of the fitted globals (order: names)
    names: list[str] = field(default_factory=list)
    effective_parameters: dict = field(default_factory=dict)   # channel → Σ leverages (fitted dof used)
    variance_factor: dict = field(default_factory=dict)        # channel → Σ(r/σ)²/dof (1 if σ is right)
    n_per_test: int = 0                        # per-test effect parameters (T_0 excluded)
    fit_info: dict = field(default_factory=dict)   # for reports: initial values, evaluations, convergence
    jacobian: np.ndarray | None = None          # ∂(standardised, projected residual)/∂(value) of *names*
    covariance: object | None = None            # a Covariance set after the fit (e.g. with prior-fixed parameters)

    @property
    def effects(self) -> list[str]:
        return [e.name for e in self.model.effects]

    @property
    def k(self) -> int:
        """Free parameters counted by the information criteria (each test's T_0 excluded: every model has it)."""
        return len(self.estimates) + self.n_per_test

    @property
    def rmse_temp_C(self) -> float:
        return math.sqrt(self.rss_temp / max(self.n_temp, 1))

    @property
    def rmse_torque_Nm(self) -> float:
        return math.sqrt(self.rss_torque / max(self.n_torque, 1))

    def _loglik_term(self) -> float:
        tiny = 1e-12
        rss_q = self.rss_torque if self.rss_torque_weighted is None else self.rss_torque_weighted
        rss_t = self.rss_temp if self.rss_temp_weighted is None else self.rss_temp_weighted
        return (self.n_temp * math.log(max(rss_t / max(self.n_temp, 1), tiny))
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
        out = {n.split(".", 1)[1]: e.as_dict() for n, e in self.estimates.items() if n.startswith(effect + ".")}
        for f, d in self.per_test.items():
            if f.startswith(effect + "."):
                out[f.split(".", 1)[1]] = self._per_test_dict(f)
        return out

    def _per_test_dict(self, family: str) -> dict:
        d = self.per_test[family]
        return {"per_test": {t: {"value": float(v), "stderr": float(s)}
                             for t, v, s in zip(self.data.tests, d["values"], d["stderr"])}, "unit": d["unit"]}

    def correlation_dict(self) -> dict:
        """{"names": [...], "matrix": [[...]]} of the fitted global parameters."""
        if self.correlation is None:
            return {"names": [], "matrix": []}
        return {"names": list(self.names), "matrix": np.round(self.correlation, 4).tolist()}

    def statistics(self) -> dict:
        """Everything the reports need beyond the parameters: per-test values, correlations, dofs."""
        return {"per_test": {f: self._per_test_dict(f) for f in self.per_test},
                "correlation": self.correlation_dict(), "effective_parameters": self.effective_parameters,
                "variance_factor": self.variance_factor}

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

def _noise_weights(data: Measurements, model: BenchModel, values: dict) -> tuple[np.ndarray, np.ndarray]:
    """1/σ per sample for both channels: the noise model attached to *data*, else estimated from it."""
    sq, st = data.torque_sigma_Nm, data.temp_sigma_C
    if sq is None or st is None:
        from rollaway.bench.noise import noise_estimate
        tau = model.state(data, values).cooling_time_constant_s
        if sq is None:
            nq = noise_estimate(data, data.torque_Nm, tau, relative=True)
            sq = nq.at(data.torque_Nm) if nq else np.full(len(data), max(float(np.std(data.torque_Nm)), 1e-6))
        if st is None:
            nt = noise_estimate(data, data.drum_temp_C, tau)
            st = nt.at(data.drum_temp_C) if nt else np.full(len(data), 1.0)
    return 1.0 / np.maximum(np.broadcast_to(st, (len(data),)), 1e-9), \
        1.0 / np.maximum(np.broadcast_to(sq, (len(data),)), 1e-9)


@single_blas_thread
def calibrate(data: Measurements, effects=(), params=None, *, free=None, start: dict | None = None,
              model: BenchModel | None = None, per_test: bool = True, statistics: bool = True,
              max_iterations: int | None = None, give_up_bic: float | None = None,
              passes: int | None = None) -> FitResult:
    """Fit μ_d, h, every parameter of *effects* and each test's T_0 to *data* (both channels jointly).

    *free* restricts the fitted global names (others stay at *start*/neutral); *start* gives
    starting values (defaults: the set's μ_d and h, each effect parameter's ``initial``; per-test
    values as arrays in ``data.tests`` order).  With ``per_test=False`` the T_0 readings are
    taken as exact (the old behaviour, for comparisons only).  Samples are weighted by the noise
    model attached to *data* (``torque_sigma_Nm``, ``temp_sigma_C``) or one estimated from it.
    *give_up_bic*: a fit that only matters below this BIC (a screen against a known one) is abandoned once its
    remaining budget cannot bring it there (:func:`rollaway.identify.solver.futile`): it then ends above it, not
    converged (``fit_info["gave_up"]``: the bar).  *passes*: at most this many passes of the globals between the
    per-test values' Gauss–Newton updates (default :data:`~rollaway.identify.fitting.MAX_OUTER`).
    """
    from rollaway.identify import memo
    k = memo.key(data, effects, params, dict(free=free, start=start, model=model, per_test=per_test,
                                             statistics=statistics, max_iterations=max_iterations,
                                             **({} if passes is None else {"passes": passes})))
    kept = memo.lookup(k)            # a fit given up below one bar answers a call with that bar or a lower one
    if kept is not None and (kept.fit_info.get("gave_up") is None
                             or give_up_bic is not None and give_up_bic <= kept.fit_info["gave_up"]):
        return kept
    fit = _calibrate(data, effects, params, free, start, model, per_test, statistics, max_iterations, give_up_bic,
                     passes)
    memo.store(k, fit)
    return fit


def _calibrate(data, effects, params, free, start, model, per_test, statistics, max_iterations,
               give_up_bic=None, passes=None) -> FitResult:
    model = model or BenchModel(params, effects)
    init = model.initial_values()
    families = model.per_test_parameters() if per_test else []
    init[INITIAL_TEMP] = data.test_initial_temp_C.copy()
    for f in families[1:]:
        init[f] = np.full(data.n_tests, model.drum.effect(f.split(".")[0]).parameter(f.split(".", 1)[1]).initial)
    for k, v in (start or {}).items():
        if k in families and np.ndim(v) == 0:
            continue            # a scalar start for a per-test family: keep the per-test starts
        init[k] = v
    free = set(model.parameter_names() if free is None else free)
    names = [n for n in model.parameter_names() if n in free]
    neutral = model.neutral_values()
    values = {n: (init[n] if n in free else (start or {}).get(n, neutral[n])) for n in model.parameter_names()}
    values.update({f: init[f] for f in families})
    if not per_test:
        values[INITIAL_TEMP] = None
    if 2 * len(data) < len(names):              # fewer residuals than globals: MINPACK cannot start
        from rollaway.identify.enough import require
        what = " + ".join(e.name for e in model.effects) or "the drum"
        require(data, len(names) + (data.n_tests if per_test else 0), f"fit {what}")
    w_t, w_q = _noise_weights(data, model, values)
    prob = Problem(model, data, names, families, values, w_t, w_q)
    bar = None
    if give_up_bic is not None:          # the BIC's log-likelihood term, its penalty (FitResult.k) taken off
        k = len(names) + sum(data.n_tests for f in families if f != INITIAL_TEMP)
        bar = float(give_up_bic) - k * math.log(2 * len(data))
    sol = prob.solve(init, jacobian=statistics, give_up_loglik=bar, passes=passes,
                     **({} if max_iterations is None else {"max_iterations": max_iterations}))
    fit = _result(model, data, sol, prob, names, families, statistics)
    if sol.gave_up:
        fit.fit_info["gave_up"] = float(give_up_bic)
    return fit


def _result(model, data, sol, prob, names, families, statistics=True) -> FitResult:
    vals = sol.values
    pred = model.predict(data, vals)
    n = len(data)
    r = sol.residual
    rt_w, rq_w = r[:n], r[n:]
    # leverages: per-test families (block diagonal) + projected globals → effective parameters per channel
    lev = np.zeros(2 * n)
    if families and sol.local_normal is not None and statistics:
        gm = np.stack(sol.local_grad, axis=1)
        inv = np.linalg.pinv(sol.local_normal)
        lev += np.einsum("ia,iab,ib->i", gm, inv[prob.rows_test], gm)
    jac = sol.jac
    if names and jac is not None and jac.size:
        lev += np.einsum("ia,ab,ib->i", jac, np.linalg.pinv(jac.T @ jac), jac)
    p_t, p_q = float(lev[:n].sum()), float(lev[n:].sum())
    dof_t, dof_q = max(n - p_t, 1.0), max(n - p_q, 1.0)
    phi_t, phi_q = float(rt_w @ rt_w) / dof_t, float(rq_w @ rq_w) / dof_q
    estimates, warnings, corr = {}, [], None
    if names and jac is None:
        for name in names:
            lo, hi = model.bounds(name)
            estimates[name] = ParameterEstimate(name, float(vals[name]), model.unit(name), math.nan, (lo, hi), lo, hi)
    elif names:
        rowscale = np.concatenate([np.full(n, 1 / np.sqrt(max(phi_t, 1e-300))),
                                   np.full(n, 1 / np.sqrt(max(phi_q, 1e-300)))])
        cov = _covariance(jac * rowscale[:, None]) * np.outer(sol.scale, sol.scale)
        se = np.sqrt(np.clip(np.diag(cov), 0, None))
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = cov / np.outer(se, se)
        tcrit = special.stdtrit(max(2 * n - p_t - p_q, 1), 0.975)
        for i, name in enumerate(names):
            lo, hi = model.bounds(name)
            v = float(vals[name])
            tol = 1e-4 * (hi - lo)
            at = "lower" if v - lo <= tol else "upper" if hi - v <= tol else ""
            s = float(se[i])
            ci = (max(lo, v - tcrit * s), min(hi, v + tcrit * s)) if np.isfinite(s) else (lo, hi)
            estimates[name] = ParameterEstimate(name, v, model.unit(name), s, ci, lo, hi, at)
            if at and not _neutral_bound(model, name, v):
                warnings.append(f"{name} = {v:.4g} is stuck at its {at} bound "
                                f"({lo if at == 'lower' else hi:g} {model.unit(name)}); the data push it out of "
                                f"the physical range or the effect is absent — its interval is not meaningful")
    per_test = {}
    if families and sol.local_normal is not None and statistics:
        scaled = sol.local_normal / np.where(np.arange(2 * n) < n, phi_t, phi_q).mean()
        inv = np.linalg.pinv(scaled)
        for a, f in enumerate(families):
            per_test[f] = {"values": np.asarray(vals[f], float), "stderr": np.sqrt(np.clip(inv[:, a, a], 0, None)),
                           "unit": model.unit(f)}
    rt = data.drum_temp_C - pred.drum_temp_C
    rq = data.torque_Nm - pred.torque_Nm
    return FitResult(model, data, vals, estimates, pred, float(rt @ rt), float(rq @ rq), n, n, warnings,
                     float(rq_w @ rq_w), float(rt_w @ rt_w), per_test, corr, names,
                     {"temperature": p_t, "torque": p_q}, {"temperature": phi_t, "torque": phi_q},
                     n_per_test=sum(data.n_tests for f in families if f != INITIAL_TEMP),
                     fit_info={"stages": [{"channel": "joint (temperature + torque)", "names": list(names),
                                           "correlation": None if corr is None else np.asarray(corr).tolist(),
                                           "nfev": int(getattr(sol, "nfev", 0)), "success": True,
                                           "peak_calls": int(getattr(sol, "peak_calls", 0))}]},
                     jacobian=None if jac is None else jac / sol.scale[None, :])


def _neutral_bound(model, name, v) -> bool:
    """An effect parameter resting on its neutral bound (the effect switched off) is not a warning."""
    if "." not in name:
        return False
    eff, par = name.split(".", 1)
    return model.drum.effect(eff).parameter(par).neutral == v or abs(model.drum.effect(eff).parameter(par).neutral - v) <= \
        1e-4 * (model.bounds(name)[1] - model.bounds(name)[0])


def _covariance(jac: np.ndarray) -> np.ndarray:
    """(JᵀJ)⁻¹ in scaled variables via eigen-decomposition; directions the data do not determine get ∞."""
    a = jac.T @ jac
    w, v = np.linalg.eigh(a)
    good = w > max(float(w.max()), 1e-300) * 1e-12
    inv_w = np.where(good, 1.0 / np.where(good, w, 1.0), np.inf)
    with np.errstate(invalid="ignore"):
        cov = (v * inv_w) @ v.T
    bad = ~good
    if np.any(bad):   # a parameter that loads on an undetermined direction has no finite error
        loads = np.abs(v[:, bad]).max(axis=1) > 1e-6
        cov = np.where(np.outer(loads, loads), np.inf, (v[:, good] / w[good]) @ v[:, good].T)
    return cov


def jacobian_at(fit: FitResult, names: list[str]) -> np.ndarray:
    """∂(standardised residual)/∂(value) of *names* (freed or not) at the fit's values, the per-test
    values profiled out: the sensitivity of the data to parameters the fit held fixed."""
    from rollaway.identify.model import DrumPlan
    m = fit.model
    brake = [n for n in names if "." not in n]
    plan = DrumPlan(m.params, tuple(dict.fromkeys([*m.free, *brake])))     # in order: a set's order is the hash seed's
    model = BenchModel(plan, m.effects)
    vals = {**model.neutral_values(), **fit.values}
    families = [f for f in model.per_test_parameters() if f in fit.values]
    w_t, w_q = _noise_weights(fit.data, model, vals)
    prob = Problem(model, fit.data, names, families, vals, w_t, w_q)
    r = prob.profile(vals)[0]
    lo = np.array([model.bounds(n)[0] for n in names])
    hi = np.array([model.bounds(n)[1] for n in names])
    x = np.array([vals[n] for n in names], float)
    scale = np.maximum(np.abs(x), 1e-3 * (hi - lo))
    return prob.projected_jacobian(vals, r, lo, hi, scale) / scale[None, :]


def evaluate(data: Measurements, effects=(), params=None, values: dict | None = None) -> FitResult:
    """The model at given values (no physical parameter fitted; each test's T_0 estimated), k = 0."""
    model = BenchModel(params, effects)
    vals = {**model.neutral_values(), **(values or {})}
    fit = calibrate(data, (), params, free=[], start=vals, model=model)
    return fit
