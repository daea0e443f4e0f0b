"""Rare roll-away rates: FORM design points and importance sampling around them, stratified over choices.

* **FORM** (first-order reliability method): the design point u* — the most probable failing car in
  the standard-normal space — by constrained minimisation (SLSQP) with forward-difference gradients
  (all d + 1 points in one vectorised call), on the model without its own scatter; ``P ≈ Φ(−β)``, β = |u*|.
* **Importance sampling**: cars drawn from a mixture of unit normals centred at the design points of
  the brake and of the tyres, plus a defensive share :data:`DEFENSIVE` of the nominal density (the
  weights φ/h then stay ≤ 1/DEFENSIVE, so the variance is finite whatever FORM missed).  Unbiased
  for any failure domain; the interval is the central limit theorem's on the weighted indicators.
* **Stratified over choices**: a ``choice`` input (occupants) makes the limit state a step function,
  which gradients cannot cross, so each combination of choices (up to :data:`MAX_STRATA`) is a
  stratum with its own design points: ``P = Σ_c w_c·P_c``.  A stratum where FORM finds no failing
  point gets a plain Monte Carlo check of :data:`CHECK_CARS` cars; if none fails it counts 0 — an
  assumption, reported as ``strata_without_failure`` — and the interval's upper end grows by the
  stratum's weight times the check's Wilson upper bound (0 failures seen is no proof of none).  Samples go, chunk after chunk, to the stratum
  with the largest share of the variance until the 95 % interval is within ±:data:`TARGET_REL_HALF_WIDTH`.
"""
from __future__ import annotations

import itertools

import numpy as np
from scipy import special

from rollaway.risk.rates import Z95, Estimate, Evaluator, Rate, wilson

TARGET_REL_HALF_WIDTH = 0.15   # importance sampling stops when its 95 % interval is within ±15 %
IS_CHUNK = 10_000
DEFENSIVE = 0.1                # share of the nominal density in the importance mixture
MAX_STRATA = 64                # more combinations of choices than this: no stratification
CHECK_CARS = 20_000            # Monte Carlo check of a stratum without a design point
BETA_SPAN = 2.0                # design points up to this much farther than the nearest are centres too [assumed]
SAME_POINT = 0.5               # design points nearer than this (in u) are one
RAYS, RAY_POINTS, RAY_RADIUS, RAY_SEED = 32, 33, 8.25, 20260  # the rays scanned for other failure regions


def design_point(ev: Evaluator, free: np.ndarray, start: np.ndarray, component: str = "least",
                 step: float = 1e-5, x0: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """FORM design point of the dimensions *free* (the others stay at *start*) and β = |u*| over them.

    The nearest point of the limit state g = 0 to the origin: ``scipy.optimize.minimize`` (SLSQP) of
    |x|²/2 subject to g(x) = 0, with forward-difference gradients (the d + 1 points in one call).  Plain
    HL-RF iterations oscillate on this limit state (a bounded μ_d input bends it strongly), SLSQP does
    not.  *x0* starts the search elsewhere than at the origin (another failure region).  Returns
    (u*, inf) where no failing point is reached.
    """
    from scipy.optimize import minimize

    u = start.astype(float).copy()
    if ev.g(u[None, :], component, scatter=False)[0] <= 0:
        return u, 0.0
    x0 = np.zeros(free.size) if x0 is None else np.asarray(x0, float)
    k = free.size
    cache = {}

    def with_grad(x):
        key = x.tobytes()
        if key not in cache:
            pts = np.repeat(u[None, :], k + 1, axis=0)
            pts[:, free] = x
            pts[np.arange(1, k + 1), free] += step
            gv = ev.g(pts, component, scatter=False)
            cache.clear()
            cache[key] = (gv[0], (gv[1:] - gv[0]) / step)
        return cache[key]

    res = minimize(lambda x: 0.5 * x @ x, x0, jac=lambda x: x, method="SLSQP",
                   constraints=[{"type": "eq", "fun": lambda x: with_grad(x)[0], "jac": lambda x: with_grad(x)[1]}],
                   options={"maxiter": 200, "ftol": 1e-10})
    u[free] = res.x
    g_end = ev.g(u[None, :], component, scatter=False)[0]
    beta = float(np.linalg.norm(res.x))
    if not np.isfinite(g_end) or abs(g_end) > 1e-3 or beta > 12:
        return u, np.inf
    return u, beta


def design_points(ev: Evaluator, free: np.ndarray, start: np.ndarray, component: str) -> list:
    """Every FORM design point within :data:`BETA_SPAN` of the nearest one: [(u*, β)], nearest first.

    A failure set may have several parts (a grade scattering through zero fails at both ends; two
    facings).  FORM from the origin finds one; rays from the origin — the ± axes of the free
    dimensions, the opposite of each point found and :data:`RAYS` random directions — are scanned on a
    radius grid in one vectorised call, and FORM starts again from each ray's first failing radius
    that lies away (> 45°) from the points already found and within the span.  Parts no ray meets
    are still missed; the defensive share keeps the estimate unbiased but the interval would not
    know, so the docs list this assumption.
    """
    first = design_point(ev, free, start, component)
    if not np.isfinite(first[1]):
        found = []
    else:
        found = [first]
    k = free.size
    rng = np.random.default_rng(RAY_SEED)
    dirs = np.vstack([np.eye(k), -np.eye(k), rng.standard_normal((RAYS, k))]
                     + [-(u[free] / max(b, 1e-12))[None, :] for u, b in found if b > 0])
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    radii = np.linspace(0.25, RAY_RADIUS, RAY_POINTS)
    pts = np.repeat(start[None, :], len(dirs) * radii.size, axis=0)
    pts[:, free] = (dirs[:, None, :] * radii[None, :, None]).reshape(-1, k)
    g = ev.g(pts, component, scatter=False).reshape(len(dirs), radii.size)
    limit = (found[0][1] + BETA_SPAN) if found else RAY_RADIUS
    hits = [(radii[np.argmax(row <= 0)], d) for row, d in zip(g, dirs) if np.any(row <= 0)]
    for r, d in sorted(hits, key=lambda h: h[0]):
        if r > limit + 0.5:
            break
        if any(b > 0 and (u[free] @ d) / b > np.cos(np.pi / 4) for u, b in found):
            continue
        u, beta = design_point(ev, free, start, component, x0=r * d)
        if np.isfinite(beta) and not any(np.linalg.norm(u[free] - v[free]) < SAME_POINT for v, _ in found):
            found.append((u, beta))
            limit = min(b for _, b in found) + BETA_SPAN
    found.sort(key=lambda f: f[1])
    return [f for f in found if f[1] <= found[0][1] + BETA_SPAN]


class _Stratum:
    """One combination of choices: its probability, its design points and the running sums of IS."""

    def __init__(self, ev, weight, fixed_u, free, dim):
        self.ev, self.weight, self.fixed_u, self.free, self.dim = ev, weight, fixed_u, free, dim
        self.centres, self.betas = [], []
        for comp in ("brake", "tyre"):
            if free.size:
                found = design_points(ev, free, fixed_u, comp)
            else:
                found = [] if ev.g(fixed_u[None, :], comp, scatter=False)[0] > 0 else [(fixed_u, 0.0)]
            for u, beta in found:
                if not any(np.linalg.norm(u[free] - c) < SAME_POINT for c in self.centres):
                    self.centres.append(u[free])
                    self.betas.append(beta)
        self.sums = np.zeros((3, 2))
        self.n = 0
        self.mc = not self.centres          # no design point: plain Monte Carlo check

    def add(self, size: int, rng) -> None:
        k = self.free.size
        u = np.repeat(self.fixed_u[None, :], size, axis=0)
        if self.mc or k == 0:
            u[:, self.free] = rng.standard_normal((size, k))
            w = np.ones(size)
        else:
            centres = np.vstack([np.zeros(k), self.centres])
            b = np.asarray(self.betas)          # shares by FORM's Φ(−β) ratio, each at least a tenth of the largest
            share = np.maximum(np.exp(-0.5 * (b ** 2 - b.min() ** 2)), 0.1)
            mix = np.r_[DEFENSIVE, (1 - DEFENSIVE) * share / share.sum()]
            x = rng.standard_normal((size, k)) + centres[rng.choice(len(mix), size=size, p=mix)]
            log_h = special.logsumexp(np.log(mix)[None, :] - 0.5 * np.sum(
                (x[:, None, :] - centres[None, :, :]) ** 2, axis=2), axis=1)
            w = np.exp(-0.5 * np.sum(x * x, axis=1) - log_h)
            u[:, self.free] = x
        m = self.ev(u)
        for i, ind in enumerate((m.fails, m.brake < 1.0, m.tyre < 1.0)):
            xw = w * ind
            self.sums[i] += (xw.sum(), (xw * xw).sum())
        self.n += size

    def mean_var(self, i: int = 0) -> tuple[float, float]:
        """(P_c, variance of its estimate) of indicator *i* (all, brake, tyres)."""
        if self.n == 0:
            return 0.0, 0.0
        p = self.sums[i, 0] / self.n
        var = max(self.sums[i, 1] / self.n - p * p, 0.0) / self.n
        if self.mc and self.sums[i, 0] == 0:     # none failed in the check: an upper bound, counted 0
            return 0.0, 0.0
        return p, var


def _strata(population, ev):
    """The strata: one per combination of choice values (or a single one)."""
    d = population.dim
    disc = [i for i, m in enumerate(population.marginals) if m.discrete]
    corr_free = all(np.all(population.correlation[i, np.arange(d) != i] == 0) for i in disc)
    combos = int(np.prod([sum(w > 0 for w in population.marginals[i].weights) for i in disc])) if disc else 1
    if not disc or not corr_free or combos > MAX_STRATA:
        return [_Stratum(ev, 1.0, np.zeros(d), np.arange(d), d)]
    free = np.array([i for i in range(d) if i not in disc], int)
    choices = []
    for i in disc:
        w = np.asarray(population.marginals[i].weights)
        cum = np.r_[0.0, np.cumsum(w)]
        choices.append([(special.ndtri(np.clip((cum[j] + cum[j + 1]) / 2, 1e-300, 1 - 1e-16)), w[j])
                        for j in range(len(w)) if w[j] > 0])
    out = []
    for combo in itertools.product(*choices):
        u0 = np.zeros(d)
        u0[disc] = [z for z, _ in combo]
        out.append(_Stratum(ev, float(np.prod([w for _, w in combo])), u0, free, d))
    return out


def importance_sampling(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """Stratified mixture importance sampling around the FORM design points (module docstring)."""
    from rollaway.risk.subset import subset

    rng = np.random.default_rng(seed)
    ev = Evaluator(population, rng)
    strata = _strata(population, ev)
    if all(s.mc for s in strata) and len(strata) == 1:
        est = subset(population, samples, seed, progress)      # no design point anywhere: subset simulation
        return Estimate(est.total, est.brake, est.tyres, est.method, est.samples + ev.calls,
                        {**est.detail, "note": "FORM found no design point; subset simulation instead"})
    for s in strata:
        s.add(CHECK_CARS if s.mc else IS_CHUNK, rng)
    live = [s for s in strata if not (s.mc and s.sums[0, 0] == 0)]
    budget = max(samples, ev.calls + IS_CHUNK)

    def total(i=0):
        mv = [s.mean_var(i) for s in strata]
        return sum(s.weight * m for s, (m, _) in zip(strata, mv)), sum(s.weight ** 2 * v for s, (_, v) in zip(strata, mv))

    while live and ev.calls < budget:
        p, var = total()
        if p > 0 and Z95 * np.sqrt(var) <= TARGET_REL_HALF_WIDTH * p and sum(s.n for s in live) >= 4 * IS_CHUNK:
            break
        # the stratum whose variance falls most per added car: the largest w²·var/n (var ∝ 1/n)
        share = [s.weight ** 2 * s.mean_var()[1] / s.n if s.mean_var()[0] > 0 else s.weight * 1e-300 for s in live]
        pick = live[int(np.argmax(share))]
        pick.add(IS_CHUNK, rng)
        if progress is not None:
            progress(IS_CHUNK)

    def rate(i):
        p, var = total(i)
        half = Z95 * np.sqrt(var)
        # a stratum whose check saw no failure counts 0, but only its check bounds it: its Wilson upper end
        unseen = sum(s.weight * wilson(0, s.n)[1] for s in strata if s.mc and s.sums[i, 0] == 0 and s.n)
        return Rate(float(p), (float(max(p - half, 0.0)), float(min(p + half + unseen, 1.0))))
    betas = [b for s in strata for b in s.betas]
    return Estimate(rate(0), rate(1), rate(2), "is", ev.calls,
                    {"beta": float(min(betas)) if betas else float("inf"), "strata": len(strata),
                     "strata_without_failure": sum(s.mc and s.sums[0, 0] == 0 for s in strata),
                     "interval": "normal approximation of the weighted mean"})


def form(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """FORM's Φ(−β) (summed over strata of choices) with an importance-sampling check whose interval is reported."""
    check = importance_sampling(population, samples, seed, progress)
    if check.method != "is":
        return check
    ev = Evaluator(population, np.random.default_rng(seed))
    p = 0.0
    for s in _strata(population, ev):
        p += s.weight * (float(special.ndtr(-min(s.betas))) if s.betas else 0.0)
    detail = {**check.detail, "check": {"method": "is", **check.total.as_dict()},
              "interval": "importance-sampling check around the design points"}
    return Estimate(Rate(p, check.total.ci95), check.brake, check.tyres, "form", check.samples + ev.calls, detail)
