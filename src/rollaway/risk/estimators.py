"""Estimators of the roll-away rate, each with its 95 % interval and its name.

All work in the standard-normal space u of the population (:meth:`Population.values_from_normal`):

* ``mc``: plain Monte Carlo, streamed in chunks of :data:`CHUNK` cars (populations larger than
  memory), optionally over a Dask cluster; the interval is Wilson's score interval
  (``scipy.stats.binomtest(...).proportion_ci``), whose coverage is close to nominal also for a few failures;
* ``form``: the first-order reliability method — the design point u* (the most probable failing car)
  by the HL-RF iteration with finite-difference gradients, ``P ≈ Φ(−β)``, β = |u*| — with an
  importance-sampling check whose interval is reported (FORM alone has none);
* ``is``: importance sampling around the design points (one per failure mode, brake and tyres,
  found by FORM) with a defensive share of the nominal density, so the weights stay bounded;
  the sample grows until the 95 % interval is within ±:data:`TARGET_REL_HALF_WIDTH` or the budget
  is spent; interval by the central limit theorem on the weighted indicators;
* ``subset``: subset simulation (Au & Beck 2001) by OpenTURNS (``ot.SubsetSampling``), its
  interval from OpenTURNS' coefficient of variation;
* ``auto``: a pilot Monte Carlo run; Monte Carlo if it sees at least :data:`AUTO_MC_FAILURES`
  failures, importance sampling otherwise.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import special, stats

from rollaway.errors import UserError
from rollaway.risk.limit_state import Margins, margins, model_draws

METHODS = ("auto", "mc", "is", "subset", "form")
CHUNK = 250_000               # cars per streamed chunk
PILOT = 100_000               # cars of the pilot run of method "auto"
AUTO_MC_FAILURES = 50         # pilot failures from which plain Monte Carlo is accurate enough (±28 %)
TARGET_REL_HALF_WIDTH = 0.15  # importance sampling stops when its 95 % interval is within ±15 %
IS_CHUNK = 20_000
DEFENSIVE = 0.1               # share of the nominal density in the importance mixture
Z95 = stats.norm.isf(0.025)


@dataclass(frozen=True)
class Rate:
    """A probability with its 95 % interval."""

    probability: float
    ci95: tuple[float, float]

    def as_dict(self) -> dict:
        return {"probability": self.probability, "ci95": list(self.ci95), "ppm": self.probability * 1e6}


@dataclass(frozen=True)
class Estimate:
    """The roll-away rate of a population: overall and per failure mode, with the method and its cost."""

    total: Rate
    brake: Rate
    tyres: Rate
    method: str
    samples: int
    detail: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        out = {**self.total.as_dict(), "method": self.method, "samples": self.samples,
               "modes": {"brake": self.brake.as_dict(), "tyres": self.tyres.as_dict()}}
        out.update(self.detail)
        return out


class Evaluator:
    """Margins of cars given by standard-normal scores, with the model's own scatter drawn alongside."""

    def __init__(self, population, rng: np.random.Generator):
        self.population, self.rng, self.calls = population, rng, 0

    def __call__(self, u: np.ndarray) -> Margins:
        u = np.atleast_2d(u)
        self.calls += len(u)
        draws = model_draws(self.population, len(u), self.rng)
        return margins(self.population, self.population.values_from_normal(u), len(u), draws)

    def g(self, u: np.ndarray, component: str = "least") -> np.ndarray:
        """Limit-state function: margin − 1 (< 0 fails); *component* ``least``, ``brake`` or ``tyre``."""
        m = self(u)
        v = {"least": m.least, "brake": m.brake, "tyre": m.tyre}[component]
        return np.where(np.isfinite(v), v, 1e6) - 1.0


def wilson(k: int, n: int) -> tuple[float, float]:
    ci = stats.binomtest(int(k), int(n)).proportion_ci(0.95, method="wilson")
    return float(ci.low), float(ci.high)


def monte_carlo(population, samples: int, seed: int | None = 0, progress=None, executor=None) -> Estimate:
    """Plain Monte Carlo over *samples* cars in chunks (local, or a Dask client as *executor*)."""
    sizes = [min(CHUNK, samples - lo) for lo in range(0, samples, CHUNK)]
    seeds = np.random.SeedSequence(seed).spawn(len(sizes))
    if executor is not None:
        counts = executor(population, sizes, seeds)
    else:
        counts = np.zeros(3, np.int64)
        for size, ss in zip(sizes, seeds):
            counts += count_chunk(population, size, ss)
            if progress is not None:
                progress(size)
    k, kb, kt = (int(c) for c in counts)
    return Estimate(Rate(k / samples, wilson(k, samples)), Rate(kb / samples, wilson(kb, samples)),
                    Rate(kt / samples, wilson(kt, samples)), "mc", samples,
                    {"interval": "Wilson score"})


def count_chunk(population, size: int, seed_seq) -> np.ndarray:
    """(failures, brake slips, tyre skids) among *size* cars drawn with *seed_seq* (a Dask task, too)."""
    rng = np.random.default_rng(seed_seq)
    m = Evaluator(population, rng)(rng.standard_normal((size, population.dim)))
    return np.array([np.sum(m.fails), np.sum(m.brake < 1.0), np.sum(m.tyre < 1.0)], np.int64)


def design_point(ev: Evaluator, dim: int, component: str = "least", iterations: int = 40,
                 step: float = 1e-4) -> tuple[np.ndarray, float]:
    """FORM design point u* (HL-RF with forward differences, all d+1 points in one call) and β = |u*|.

    Returns (u*, inf) when the limit state does not approach 0 (no failure of that mode is reachable).
    """
    u = np.zeros(dim)
    g0 = ev.g(u[None, :], component)[0]
    if g0 <= 0:
        return u, 0.0
    for _ in range(iterations):
        pts = np.vstack([u, u + step * np.eye(dim)])
        gv = ev.g(pts, component)
        g, grad = gv[0], (gv[1:] - gv[0]) / step
        norm2 = float(grad @ grad)
        if norm2 <= 1e-300:
            return u, np.inf
        new = (grad @ u - g) / norm2 * grad
        if np.linalg.norm(new - u) > 3.0:                # damped: a long step overshoots a curved surface
            new = u + 3.0 * (new - u) / np.linalg.norm(new - u)
        done = np.linalg.norm(new - u) < 1e-4 * max(1.0, np.linalg.norm(u)) and abs(g) < 1e-4
        u = new
        if done:
            break
    g_end = ev.g(u[None, :], component)[0]
    if abs(g_end) > 0.05 or np.linalg.norm(u) > 12:
        return u, np.inf
    return u, float(np.linalg.norm(u))


def form(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """FORM's Φ(−β) with an importance-sampling check (whose interval is the one reported)."""
    check = importance_sampling(population, samples, seed, progress)
    beta = check.detail["beta"]
    p = float(special.ndtr(-beta)) if np.isfinite(beta) else 0.0
    detail = {**check.detail, "check": {"method": "is", **check.total.as_dict()},
              "interval": "importance-sampling check around the design point"}
    return Estimate(Rate(p, check.total.ci95), check.brake, check.tyres, "form", check.samples, detail)


def importance_sampling(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """Mixture importance sampling around the FORM design points of the brake and the tyres."""
    rng = np.random.default_rng(seed)
    ev = Evaluator(population, rng)
    d = population.dim
    if d == 0:
        return monte_carlo(population, min(samples, CHUNK), seed)
    centres, betas = [], []
    for comp in ("brake", "tyre"):
        u, beta = design_point(ev, d, comp)
        if np.isfinite(beta):
            centres.append(u)
            betas.append(beta)
    beta = min(betas) if betas else np.inf
    if not centres:                                   # no failure within reach: an upper bound by MC
        est = monte_carlo(population, min(samples, CHUNK), seed)
        return Estimate(est.total, est.brake, est.tyres, "is", est.samples + ev.calls,
                        {"beta": float("inf"), "interval": "Wilson score (no design point: no failure found)"})
    centres = np.array(centres)
    w_mix = np.r_[DEFENSIVE, np.full(len(centres), (1 - DEFENSIVE) / len(centres))]
    sums = np.zeros((3, 2))          # per indicator (all, brake, tyres): Σ x, Σ x²
    n = 0
    budget = max(samples - ev.calls, IS_CHUNK)
    while n < budget:
        size = min(IS_CHUNK, budget - n)
        comp = rng.choice(len(w_mix), size=size, p=w_mix)
        shift = np.vstack([np.zeros(d), centres])[comp]
        u = rng.standard_normal((size, d)) + shift
        log_phi = -0.5 * np.sum(u * u, axis=1)
        log_h = special.logsumexp(np.log(w_mix)[None, :] - 0.5 * np.sum(
            (u[:, None, :] - np.vstack([np.zeros(d), centres])[None, :, :]) ** 2, axis=2), axis=1)
        w = np.exp(log_phi - log_h)
        m = ev(u)
        for i, ind in enumerate((m.fails, m.brake < 1.0, m.tyre < 1.0)):
            x = w * ind
            sums[i] += (x.sum(), (x * x).sum())
        n += size
        if progress is not None:
            progress(size)
        p, se = sums[0, 0] / n, np.sqrt(max(sums[0, 1] / n - (sums[0, 0] / n) ** 2, 0.0) / n)
        if p > 0 and Z95 * se <= TARGET_REL_HALF_WIDTH * p and n >= 4 * IS_CHUNK:
            break

    def rate(i):
        p = sums[i, 0] / n
        se = np.sqrt(max(sums[i, 1] / n - p * p, 0.0) / n)
        return Rate(float(p), (float(max(p - Z95 * se, 0.0)), float(min(p + Z95 * se, 1.0))))
    return Estimate(rate(0), rate(1), rate(2), "is", ev.calls,
                    {"beta": float(beta), "design_points": len(centres),
                     "interval": "normal approximation of the weighted mean"})


def subset(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """Subset simulation by OpenTURNS; per-mode rates from the final level are not available (NaN)."""
    import openturns as ot

    rng = np.random.default_rng(seed)
    ev = Evaluator(population, rng)
    d = population.dim
    if d == 0:
        raise UserError("method 'subset' needs at least one varied input in [vary]")
    ot.RandomGenerator.SetSeed(int(seed or 0))
    f = ot.PythonFunction(d, 1, func_sample=lambda x: ev.g(np.asarray(x))[:, None].tolist())
    event = ot.ThresholdEvent(ot.CompositeRandomVector(f, ot.RandomVector(ot.Normal(d))), ot.Less(), 0.0)
    algo = ot.SubsetSampling(event)
    per_level = max(1000, min(samples // 8, 100_000))
    algo.setMaximumOuterSampling(1)
    algo.setBlockSize(per_level)
    algo.run()
    res = algo.getResult()
    p = float(res.getProbabilityEstimate())
    cv = float(res.getCoefficientOfVariation()) if p > 0 else 0.0
    half = Z95 * cv * p
    nan = Rate(float("nan"), (float("nan"), float("nan")))
    return Estimate(Rate(p, (max(p - half, 0.0), min(p + half, 1.0))), nan, nan, "subset", ev.calls,
                    {"levels": int(algo.getStepsNumber()), "interval": "OpenTURNS coefficient of variation"})


def estimate(population, method: str = "auto", samples: int = 1_000_000, seed: int | None = 0,
             progress=None, executor=None) -> Estimate:
    """The roll-away rate of *population* by *method* (module docstring) with at most about *samples* cars."""
    if method not in METHODS:
        from rollaway.errors import check_choice
        check_choice(method, METHODS, "--method")
    if not (isinstance(samples, (int, np.integer)) and samples >= 100):
        raise UserError(f"--samples {samples} must be a whole number ≥ 100, e.g. 1000000")
    if method == "auto":
        pilot = monte_carlo(population, min(PILOT, samples), seed, progress)
        if pilot.total.probability * pilot.samples >= AUTO_MC_FAILURES or population.dim == 0:
            method = "mc"
        else:
            method = "is"
    if method == "mc":
        return monte_carlo(population, samples, seed, progress, executor)
    return {"is": importance_sampling, "form": form, "subset": subset}[method](population, samples, seed, progress)
