"""Estimators of the roll-away rate, each with its 95 % interval and its name.

All work in the standard-normal space u of the population (:meth:`Population.values_from_normal`):

* ``mc``: plain Monte Carlo, streamed in chunks of :data:`CHUNK` cars (populations larger than
  memory), optionally over a Dask cluster; the interval is Wilson's score interval
  (``scipy.stats.binomtest(...).proportion_ci``), whose coverage is close to nominal also for a few failures;
* ``form``, ``is``: the first-order reliability method and importance sampling around its design
  points, stratified over choices (:mod:`rollaway.risk.importance`);
* ``subset``: subset simulation by OpenTURNS (:mod:`rollaway.risk.subset`), which needs no design point;
  importance sampling falls back to it when FORM finds none;
* ``auto``: a pilot Monte Carlo run; Monte Carlo if it sees at least :data:`AUTO_MC_FAILURES`
  failures, importance sampling otherwise.
"""
from __future__ import annotations

import numpy as np

from rollaway.errors import UserError
from rollaway.risk.rates import Estimate, Evaluator, Rate, wilson

METHODS = ("auto", "mc", "is", "subset", "form")
CHUNK = 250_000               # cars per streamed chunk
PILOT = 100_000               # cars of the pilot run of method "auto"
AUTO_MC_FAILURES = 50         # pilot failures from which plain Monte Carlo is accurate enough (±28 %)


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


def estimate(population, method: str = "auto", samples: int = 1_000_000, seed: int | None = 0,
             progress=None, executor=None) -> Estimate:
    """The roll-away rate of *population* by *method* (module docstring) with at most about *samples* cars."""
    if method not in METHODS:
        from rollaway.errors import check_choice
        check_choice(method, METHODS, "--method")
    if not (isinstance(samples, (int, np.integer)) and samples >= 100):
        raise UserError(f"--samples {samples} must be a whole number ≥ 100, e.g. 1000000")
    if seed is not None and not (isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and seed >= 0):
        raise UserError(f"--seed {seed} must be a whole number ≥ 0, e.g. 0")
    spent = 0
    if population.dim == 0 and method != "mc":       # nothing varied (a calibrated model's own scatter at most)
        est = monte_carlo(population, samples, seed, progress, executor)
        return Estimate(est.total, est.brake, est.tyres, "mc", est.samples,
                        {**est.detail, "note": f"nothing in [vary]: plain Monte Carlo instead of '{method}'"})
    if method == "auto":
        pilot = monte_carlo(population, min(PILOT, samples), seed, progress)
        if pilot.total.probability * pilot.samples >= AUTO_MC_FAILURES or population.dim == 0:
            return monte_carlo(population, samples, seed, progress, executor)   # the pilot's cars are its first
        method, spent = "is", pilot.samples
    if method == "mc":
        return monte_carlo(population, samples, seed, progress, executor)
    from rollaway.risk.importance import form, importance_sampling
    from rollaway.risk.subset import subset
    est = {"is": importance_sampling, "form": form, "subset": subset}[method](population, samples, seed, progress)
    if spent:
        est = Estimate(est.total, est.brake, est.tyres, est.method, est.samples + spent,
                       {**est.detail, "pilot_mc_samples": spent})
    return est
