"""A rate with its 95 % interval, an estimate (overall and per failure mode), and the limit-state evaluator.

Shared by the estimators (:mod:`rollaway.risk.estimators`, :mod:`rollaway.risk.importance`,
:mod:`rollaway.risk.subset`); every estimator works in the population's standard-normal space.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import stats

from rollaway.risk.limit_state import Margins, margins, model_draws

Z95 = float(stats.norm.isf(0.025))


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

    def g(self, u: np.ndarray, component: str = "least", scatter: bool = True) -> np.ndarray:
        """Limit-state function: margin − 1 (< 0 fails); *component* ``least``, ``brake`` or ``tyre``;
        without *scatter* the model's own uncertainty is left out (a deterministic function for FORM)."""
        if scatter:
            m = self(u)
        else:
            u = np.atleast_2d(u)
            self.calls += len(u)
            m = margins(self.population, self.population.values_from_normal(u), len(u))
        v = {"least": m.least, "brake": m.brake, "tyre": m.tyre}[component]
        return np.where(np.isfinite(v), v, 1e6) - 1.0


def wilson(k: int, n: int) -> tuple[float, float]:
    """Wilson's score interval of k failures in n cars (95 %)."""
    ci = stats.binomtest(int(k), int(n)).proportion_ci(0.95, method="wilson")
    return float(ci.low), float(ci.high)


