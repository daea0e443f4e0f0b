"""Held-out truths for the risk tests, computed without any rollaway.risk code.

The margin of a car comes from the hold package's closed forms (:func:`rollaway.hold.min_brake_margin`,
:func:`rollaway.hold.tyre_adhesion_margin`, eqs. 17b, 22, 23 of the paper, monotone torque over the hold);
the distributions are scipy.stats objects built here from the numbers of the population file; a rate is
the probability of the failing set, found by a dense grid + Brent roots and integrated by the CDF
(one input) or by adaptive quadrature (two inputs); Sobol total indices by a plain-numpy pick-freeze
(Jansen) estimate of the least brake margin.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy import integrate, optimize, stats

from rollaway.hold import min_brake_margin, tyre_adhesion_margin
from rollaway.model.parameters import paper

BASE = dict(grade_pct=20.0, direction="uphill", occupants=5, hand_force_N=400.0, duration_s=300.0,
            initial_drum_temp_C=200.0)
HOLD_ARGS = {"mu_drum": "mu_drum", "gap_m": "gap_m", "initial_drum_temp_C": "initial_temp_C"}
SCEN = ("grade_pct", "occupants", "hand_force_N", "duration_s")
PHYSICAL = {"hand_force_N": (0.0, 5000.0), "grade_pct": (-99.999, 100.0)}   # the hold check's own limits


def least_margins(values: dict, base: dict = BASE):
    """(least brake margin, least tyre margin) of cars given by *values* ({name: array}) over the file's facings."""
    case = {**base, **{k: np.clip(v, *PHYSICAL[k]) if k in PHYSICAL else v for k, v in values.items()}}
    dirs = ("uphill", "downhill") if case["direction"] == "both" else (case["direction"],)
    fields = {k: np.asarray(v, float) for k, v in case.items()
              if k not in SCEN and k not in HOLD_ARGS and k != "direction"}
    params = dataclasses.replace(paper(), **fields) if fields else paper()
    kw = {HOLD_ARGS[k]: np.asarray(case[k], float) for k in HOLD_ARGS if k in case}
    brake = tyre = np.inf
    for d in dirs:
        brake = np.minimum(brake, min_brake_margin(params, case["hand_force_N"], case["grade_pct"], d,
                                                   case["occupants"], case["duration_s"], **kw))
        tyre = np.minimum(tyre, tyre_adhesion_margin(params, case["grade_pct"], d, case["occupants"]))
    return np.broadcast_arrays(np.asarray(brake, float), np.asarray(tyre, float))


def fails_margin(values: dict, base: dict = BASE) -> np.ndarray:
    b, t = least_margins(values, base)
    return np.minimum(b, t) - 1.0


def frozen(spec: dict):
    """A scipy distribution (and its truncation) from a [vary] table like {"normal": [400, 35]}."""
    kind = next(k for k in spec if k != "truncate")
    a = spec[kind]
    d = {"uniform": lambda: stats.uniform(a[0], a[1] - a[0]), "normal": lambda: stats.norm(a[0], a[1]),
         "lognormal": lambda: stats.lognorm(a[1], scale=a[0]),
         "triangular": lambda: stats.triang((a[1] - a[0]) / (a[2] - a[0]), a[0], a[2] - a[0])}[kind]()
    if "truncate" in spec:
        lo, hi = spec["truncate"]
        flo, fhi = d.cdf(lo), d.cdf(hi)

        class _T:   # the truncated law through the CDF
            def cdf(self, x):
                return np.clip((d.cdf(x) - flo) / (fhi - flo), 0.0, 1.0)

            def pdf(self, x):
                return np.where((x >= lo) & (x <= hi), d.pdf(x) / (fhi - flo), 0.0)

            def ppf(self, q):
                return d.ppf(flo + q * (fhi - flo))
        return _T()
    return d


def rate_one(name: str, spec: dict, base: dict = BASE, grid: int = 4001) -> float:
    """Exact rate with one varied input: the probability of the set where the least margin is < 1."""
    if "choice" in spec:
        vals = np.asarray(spec["choice"], float)
        w = np.asarray(spec.get("weights", np.ones(len(vals))), float)
        f = np.array([fails_margin({name: v}, base) for v in vals]).ravel()
        return float(np.sum(w[f < 0]) / w.sum())
    d = frozen(spec)
    q = np.r_[1e-15, np.linspace(0, 1, grid)[1:-1], 1 - 1e-15]
    x = np.unique(d.ppf(q))
    g = fails_margin({name: x}, base).ravel()
    h = lambda v: float(fails_margin({name: v}, base).ravel()[0])  # noqa: E731
    edges = [x[0]] + [optimize.brentq(h, x[i], x[i + 1], xtol=1e-13, rtol=1e-14)
                      for i in np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))] + [x[-1]]
    p = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        if h(0.5 * (a + b)) < 0:
            p += float(d.cdf(b) - d.cdf(a))
    if g[0] < 0:            # the far lower tail below the grid
        p += float(d.cdf(x[0]))
    if g[-1] < 0:
        p += float(1 - d.cdf(x[-1]))
    return p


def force_threshold(base: dict = BASE, **values) -> float:
    """Hand force at which the least margin is exactly 1 (the margin rises with the force)."""
    h = lambda f: float(fails_margin({"hand_force_N": f, **values}, base).ravel()[0])  # noqa: E731
    if h(1e-6) >= 0:
        return 0.0
    if h(1000.0) < 0:
        return np.inf
    return optimize.brentq(h, 1e-6, 1000.0, xtol=1e-12)


def rate_force_and(name: str, spec: dict, force: dict, base: dict = BASE, rho: float = 0.0) -> float:
    """Two inputs, the hand force and *name*, with a Gaussian copula of correlation *rho*: in normal scores
    z₁ (of *name*) and z₂ (of the force), P = ∫ φ(z₁) Φ((z₂*(z₁) − ρ z₁)/√(1 − ρ²)) dz₁ by quadrature,
    z₂* the score of the threshold force of the car with that *name* value."""
    d, df = frozen(spec), frozen(force)

    def f(z1):
        fstar = force_threshold(base, **{name: float(d.ppf(stats.norm.cdf(z1)))})
        z2 = stats.norm.ppf(np.clip(df.cdf(fstar), 0.0, 1.0))
        return stats.norm.pdf(z1) * stats.norm.cdf((z2 - rho * z1) / np.sqrt(1 - rho * rho))
    zs = np.linspace(-7.0, 7.0, 57)
    return float(sum(integrate.quad(f, a, b, epsabs=1e-16, epsrel=1e-8, limit=100)[0] for a, b in zip(zs[:-1], zs[1:])))


def sample(spec: dict, u: np.ndarray) -> np.ndarray:
    """Values of a [vary] table for uniform scores *u* (inverse CDF; choice by cumulative weights)."""
    if "choice" in spec:
        vals = np.asarray(spec["choice"], float)
        w = np.asarray(spec.get("weights", np.ones(len(vals))), float)
        return vals[np.minimum(np.searchsorted(np.cumsum(w) / w.sum(), u, side="right"), len(vals) - 1)]
    return frozen(spec).ppf(u)


def sobol_total(vary: dict, base: dict = BASE, n: int = 1_000_000, seed: int = 12345, chunk: int = 200_000):
    """Jansen's pick-freeze total indices (and Saltelli first-order) of the least brake margin, plain numpy."""
    names = list(vary)
    k = len(names)
    rng = np.random.default_rng(seed)
    sums_t, sums_f, fa, fa2, m = np.zeros(k), np.zeros(k), 0.0, 0.0, 0
    for lo in range(0, n, chunk):
        size = min(chunk, n - lo)
        a, b = rng.random((size, k)), rng.random((size, k))
        va = {nm: sample(vary[nm], a[:, i]) for i, nm in enumerate(names)}
        vb = {nm: sample(vary[nm], b[:, i]) for i, nm in enumerate(names)}
        ya, yb = least_margins(va, base)[0], least_margins(vb, base)[0]
        for i, nm in enumerate(names):
            yab = least_margins({**va, nm: vb[nm]}, base)[0]
            sums_t[i] += np.sum((ya - yab) ** 2) / 2
            sums_f[i] += np.sum(yb * (yab - ya))
        fa += np.sum(ya) + np.sum(yb)
        fa2 += np.sum(ya ** 2) + np.sum(yb ** 2)
        m += size
    var = fa2 / (2 * m) - (fa / (2 * m)) ** 2
    return dict(zip(names, sums_t / m / var)), dict(zip(names, sums_f / m / var))
