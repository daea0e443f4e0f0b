"""The design that meets a target: the least (or greatest) value of one input keeping the rate ≤ P.

*name* is a fixed input of the population (``hand_force_N``, ``grade_pct``, any parameter such as
``drum_radius_m``), a spec limit of a varied one (``mu_drum.lower``: the distribution truncated
there — the parts below the limit are rejected at the supplier's inspection), or a varied input
itself: then its nominal (median) value, the whole distribution moved with it and its scatter kept.

The rate is estimated with **common random numbers**: one set of standard-normal scores (and model
draws) serves every trial value, so the estimated rate is a monotone step function of a monotone
input and bisection finds the crossing exactly for that sample.  Where the target is too rare for
the Monte Carlo sample (fewer than :data:`MC_FAILURES` expected failures) every trial value is
estimated by importance sampling with the same seed instead.  The safe side (least or greatest) is
the end of the search range where the rate is lower.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rollaway.errors import UserError
from rollaway.risk.estimators import wilson
from rollaway.risk.importance import importance_sampling
from rollaway.risk.limit_state import margins, model_draws
from rollaway.risk.population import RANGES, Population

MC_FAILURES = 100            # expected failures at the target from which plain MC with common numbers is used
CURVE_POINTS = 25
MAX_MC_CARS = 1_000_000      # cars of the common-random-number sample (the memory of one evaluation)
WHOLE = ("occupants",)       # inputs that take whole numbers: searched value by value


@dataclass(frozen=True)
class Design:
    """The value of *name* that keeps the rate ≤ *target*, the rate there and the curve rate(value)."""

    name: str
    value: float
    probability: float
    ci95: tuple[float, float]
    target: float
    side: str                      # "least" or "greatest": which end of the range is safe
    curve: list[tuple[float, float]]
    method: str
    samples: int

    def as_dict(self) -> dict:
        return {"name": self.name, "value": self.value, "probability": self.probability, "ci95": list(self.ci95),
                "ppm": self.probability * 1e6, "target": self.target, "side": self.side, "method": self.method,
                "samples": self.samples, "curve": [[v, p] for v, p in self.curve]}


def _setter(population: Population, name: str):
    """(function value → population, search range, current value) for a fixed input or a spec limit."""
    if "." in name:
        base, side = name.rsplit(".", 1)
        if side not in ("lower", "upper"):
            raise UserError(f"--design {name}: a spec limit is NAME.lower or NAME.upper (e.g. mu_drum.lower)")
        m = population.marginal(base)
        lo, hi = m.support()
        if not math.isfinite(lo) or not math.isfinite(hi):
            lo, hi = float(m.from_normal(-6.0)), float(m.from_normal(6.0))
        now = lo if side == "lower" else hi
        span = (lo, m.median()) if side == "lower" else (m.median(), hi)
        return (lambda v: population.with_marginal(m.with_bound(side, v))), span, now
    if name in population.names:           # a varied input: its nominal (median) value, the scatter kept
        m = population.marginal(name)
        now = m.median()
        lo, hi = RANGES[name]
        if now > 0 and name not in WHOLE:
            lo, hi = max(lo, now / 4.0), min(hi, now * 4.0)
        return (lambda v: population.with_marginal(m.shifted_to(v))), (lo, hi), now
    now = population.fixed(name)
    lo, hi = RANGES[name]
    if now > 0 and name not in WHOLE:
        lo, hi = max(lo, now / 4.0), min(hi, now * 4.0)
    return (lambda v: population.with_fixed(name, v)), (lo, hi), now


def _log_root(rate, target: float, good: float, bad: float, tol: float) -> float:
    """The value between *good* (rate ≤ target) and *bad* where log rate = log target (Brent), then
    stepped towards *good* until its own estimate meets the target."""
    from scipy.optimize import brentq

    value = brentq(lambda v: math.log(max(rate(v), 1e-300)) - math.log(target), good, bad, xtol=tol)
    step = math.copysign(tol, good - value)
    while rate(value) > target and (good - value) * step > 0:
        value += step
    return value


def design(population: Population, name: str, target: float, samples: int = 1_000_000, seed: int | None = 0,
           tolerance: float | None = None) -> Design:
    """Least or greatest value of *name* whose roll-away rate is ≤ *target* (module docstring)."""
    if not (isinstance(target, (int, float)) and 0 < target < 1):
        raise UserError(f"--target {target!r} must be a probability between 0 and 1, e.g. 1e-4 (100 ppm)")
    m = population.model
    if population.dim == 0 and m.covariance is None and not m.predictive and not m.alternatives:
        raise UserError(f"--design {name}: the population varies nothing (no [vary] table) and its model has no "
                        f"scatter of its own, so its rate is 0 or 1; add the inputs that scatter in production, or use 'rollaway hold' for the one car")
    make, (lo, hi), _ = _setter(population, name)
    n = int(min(samples, MAX_MC_CARS))
    rng = np.random.default_rng(seed)
    crn = target * n >= MC_FAILURES
    tol = tolerance if tolerance is not None else (1e-4 if crn else 1e-5) * (hi - lo)
    if crn:
        u = rng.standard_normal((n, population.dim))
        draws = model_draws(population, n, rng)
        method = "mc (common random numbers)"

        def rate(v):
            m = margins(p := make(v), p.values_from_normal(u), n, draws)
            k = int(np.sum(m.fails))
            return k / n, wilson(k, n)
    else:
        method = "is (same seed at every value)"

        def rate(v):
            e = importance_sampling(make(v), samples, seed)
            return e.total.probability, e.total.ci95
    if name in WHOLE:
        return _whole_design(name, target, rate, range(math.ceil(lo), math.floor(hi) + 1), method, n)
    r_lo, r_hi = rate(lo)[0], rate(hi)[0]
    side = "least" if r_hi <= r_lo else "greatest"
    good, bad = (hi, lo) if side == "least" else (lo, hi)
    if min(r_lo, r_hi) > target:
        raise UserError(f"--design {name}: no value in [{lo:g}, {hi:g}] keeps the rate ≤ {target:g} (the best end "
                        f"gives {min(r_lo, r_hi):.3g}); the target needs more than this input")
    if max(r_lo, r_hi) <= target:
        value = bad                   # the whole range meets the target: the worst end still does
    elif crn:                         # a step function of the value: bisection to the step
        while abs(good - bad) > tol:
            mid = 0.5 * (good + bad)
            if rate(mid)[0] <= target:
                good = mid
            else:
                bad = mid
        value = good
    else:                             # importance sampling, same seed: smooth in the value, Brent on log P
        value = _log_root(lambda v: rate(v)[0], target, good, bad, tol)
    p, ci = rate(value)
    width = max(abs(value) * 0.25, (hi - lo) / 20)
    grid = np.linspace(max(lo, value - width), min(hi, value + width), CURVE_POINTS if crn else CURVE_POINTS // 2)
    curve = [(float(v), float(rate(v)[0])) for v in grid]
    return Design(name, float(value), float(p), (float(ci[0]), float(ci[1])), float(target), side, curve, method, n)


def _whole_design(name: str, target: float, rate, values, method: str, n: int) -> Design:
    """:func:`design` for an input of whole numbers (:data:`WHOLE`): the rate at every value, the safe end the one
    of lower rate, the value furthest from it that still meets *target*."""
    est = {v: rate(float(v)) for v in values}
    curve = [(float(v), float(p)) for v, (p, _) in est.items()]
    first, last = curve[0][1], curve[-1][1]
    side = "least" if last <= first else "greatest"
    ok = [v for v, (p, _) in est.items() if p <= target]
    if not ok:
        raise UserError(f"--design {name}: no value from {min(est)} to {max(est)} keeps the rate ≤ {target:g} (the "
                        f"best gives {min(p for p, _ in est.values()):.3g}); the target needs more than this input")
    value = min(ok) if side == "least" else max(ok)
    p, ci = est[value]
    return Design(name, float(value), float(p), (float(ci[0]), float(ci[1])), float(target), side, curve, method, n)


def design_chart(d: Design, path, title: str = "") -> str:
    """Rate against the designed input, the target and the chosen value (PNG, log rate axis)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = np.array([c[0] for c in d.curve])
    p = np.array([c[1] for c in d.curve])
    fig, ax = plt.subplots(figsize=(7, 4))
    floor = min(d.target / 100, np.min(p[p > 0]) if np.any(p > 0) else d.target / 100)
    ax.semilogy(v[p > 0], p[p > 0], "o-", color="#2c3e50", label="roll-away rate")
    if np.any(p <= 0):
        ax.semilogy(v[p <= 0], np.full(np.sum(p <= 0), floor), "o", mfc="none", color="#7f8c8d",
                    label="none rolled away in the sample")
    ax.axhline(d.target, color="#c0392b", ls="--", label=f"target {d.target * 1e6:g} ppm")
    ax.axvline(d.value, color="#27ae60", ls=":", label=f"{d.side} {d.name} = {d.value:.4g}")
    ax.set_xlabel(d.name)
    ax.set_ylabel("probability of rolling away")
    ax.set_title(title or f"Design: {d.name} for ≤ {d.target * 1e6:g} ppm")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return str(path)
