"""Subset simulation (Au & Beck 2001) by OpenTURNS: rare rates without a design point.

Why OpenTURNS: its ``SubsetSampling`` (conditional levels at p₀ = 0.1, modified Metropolis chains in
the standard-normal space) is a tested implementation; it needs no gradient, so bounded and discrete
inputs are no obstacle.  Its own coefficient of variation ignores the correlation of the chains and is
too narrow (measured: two seeds' intervals did not overlap), so the interval here comes from
independent runs instead.
"""
from __future__ import annotations

import numpy as np
from scipy import stats

from rollaway.errors import UserError
from rollaway.risk.rates import Estimate, Evaluator, Rate

SUBSET_RUNS = 4               # independent subset-simulation runs: their spread is the interval


def _subset_run(ev: Evaluator, d: int, per_level: int, seed: int, component: str) -> float:
    import openturns as ot

    ot.RandomGenerator.SetSeed(int(seed))
    f = ot.PythonFunction(d, 1, func_sample=lambda x: ev.g(np.asarray(x), component)[:, None].tolist())
    event = ot.ThresholdEvent(ot.CompositeRandomVector(f, ot.RandomVector(ot.Normal(d))), ot.Less(), 0.0)
    algo = ot.SubsetSampling(event)
    algo.setMaximumOuterSampling(1)
    algo.setBlockSize(per_level)
    algo.run()
    return float(algo.getResult().getProbabilityEstimate())


def subset(population, samples: int, seed: int | None = 0, progress=None) -> Estimate:
    """Subset simulation by OpenTURNS, :data:`SUBSET_RUNS` independent runs per quantity (the rate, the
    brake's, the tyres'); estimate = their mean, interval = Student's t on their spread (OpenTURNS' own
    coefficient of variation ignores the correlation of its Markov chains and is too narrow)."""
    d = population.dim
    if d == 0:
        raise UserError("method 'subset' needs at least one varied input in [vary]")
    ev = Evaluator(population, np.random.default_rng(seed))
    per_level = int(max(1000, min(samples // (3 * SUBSET_RUNS * 8), 100_000)))
    base = int(np.random.SeedSequence(seed).generate_state(1)[0] % 2**30)
    rates = []
    for j, comp in enumerate(("least", "brake", "tyre")):
        runs = np.array([_subset_run(ev, d, per_level, base + 97 * j + r, comp) for r in range(SUBSET_RUNS)])
        p = float(runs.mean())
        half = float(stats.t.isf(0.025, SUBSET_RUNS - 1) * runs.std(ddof=1) / np.sqrt(SUBSET_RUNS))
        rates.append(Rate(p, (max(p - half, 0.0), min(p + half, 1.0))))
        if progress is not None:
            progress(0)
    return Estimate(rates[0], rates[1], rates[2], "subset", ev.calls,
                    {"runs": SUBSET_RUNS, "samples_per_level": per_level,
                     "interval": "Student's t over independent subset-simulation runs"})
