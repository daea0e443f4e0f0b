"""What drives the rate: Sobol indices of the least brake margin over the hold, per varied name.

SALib does the statistics (why SALib: its Saltelli/Jansen estimators and their bootstrap intervals are
the tested reference implementation; writing them again would be a copy without its tests):
``SALib.sample.sobol.sample`` draws the scrambled Sobol' design of N·(d + 2) points on [0, 1]^d
(first and total indices, no second order), the points become standard-normal scores and then
cars through the population's copula and marginals, and ``SALib.analyze.sobol.analyze`` returns
the first-order index (Saltelli 2010) and the total index (Jansen 1999) with 95 % bootstrap intervals.

Assumptions, said where the numbers are used:

* the indices are those of the *independent* normal scores; with a ``[[correlation]]`` an input's index
  includes what it carries of the inputs correlated with it;
* a calibrated model's own scatter (competing effect sets, fitted values, model error) is not a named
  input: each base row of the design keeps one draw of it for its A-matrix points and another for its
  B point, so it counts as unexplained variance (the indices of the names then sum to less than 1);
* a margin that is not finite (a self-locking shoe, a flat road) is replaced by the largest finite one.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import special

from rollaway.errors import UserError
from rollaway.risk.limit_state import margins, model_draws

BASE_SAMPLES = 2 ** 13           # N of the Saltelli design: N·(d + 2) model evaluations


@dataclass(frozen=True)
class Sensitivity:
    """First and total Sobol indices of the least brake margin, each with its 95 % interval."""

    names: tuple[str, ...]
    first: np.ndarray
    first_ci: np.ndarray        # half-widths of the 95 % intervals
    total: np.ndarray
    total_ci: np.ndarray
    evaluations: int

    def as_dict(self) -> dict:
        return {n: {"first": float(self.first[i]), "total": float(self.total[i]),
                    "first_ci95": [float(self.first[i] - self.first_ci[i]), float(self.first[i] + self.first_ci[i])],
                    "total_ci95": [float(self.total[i] - self.total_ci[i]), float(self.total[i] + self.total_ci[i])]}
                for i, n in enumerate(self.names)}

    def ranked(self) -> list[str]:
        return [self.names[i] for i in np.argsort(-self.total)]


def _take(draws: dict | None, src: np.ndarray) -> dict | None:
    """Model draws of a pool, re-indexed: row r of the result is row ``src[r]`` of the pool."""
    if draws is None:
        return None
    n_pool = len(draws["eps"])
    owner = np.zeros(n_pool, int)
    for k, (idx, _, _) in enumerate(draws["groups"]):
        owner[idx] = k
    own = owner[src]
    groups = [(np.flatnonzero(own == k), m, {name: v[src] for name, v in fitted.items()})
              for k, (_, m, fitted) in enumerate(draws["groups"])]
    out = {"groups": groups, "effects": {k: v[src] for k, v in draws["effects"].items()}, "eps": draws["eps"][src]}
    if "start" in draws:
        out["start"] = (draws["start"][0][src], draws["start"][1])
    return out


def sobol_indices(population, base_samples: int = BASE_SAMPLES, seed: int | None = 0) -> Sensitivity:
    """Sobol first and total indices of the least brake margin for every varied name (module docstring)."""
    from SALib.analyze import sobol as sobol_analyze
    from SALib.sample import sobol as sobol_sample

    d = population.dim
    if d == 0:
        raise UserError("--sensitivity needs at least one varied input in the population's [vary] table")
    if not (isinstance(base_samples, (int, np.integer)) and base_samples >= 64):
        raise UserError(f"sensitivity base samples {base_samples} must be a whole number ≥ 64, e.g. 8192")
    n = 1 << int(np.ceil(np.log2(base_samples)))           # Sobol' designs balance at powers of two
    problem = {"num_vars": d, "names": list(population.names), "bounds": [[0.0, 1.0]] * d}
    x = sobol_sample.sample(problem, n, calc_second_order=False, scramble=True, seed=seed)
    u = special.ndtri(np.clip(x, 1e-12, 1 - 1e-12))
    rng = np.random.default_rng(seed)
    pool = model_draws(population, 2 * n, rng)
    row = np.arange(len(u)) // (d + 2)
    is_b = np.arange(len(u)) % (d + 2) == d + 1
    draws = _take(pool, np.where(is_b, n + row, row))
    brake = margins(population, population.values_from_normal(u), len(u), draws).brake
    finite = np.isfinite(brake)
    if not finite.any():
        raise UserError("every sampled car self-locks or stands on a flat road: the brake margin is infinite "
                        "everywhere; there is nothing to apportion")
    y = np.where(finite, brake, np.max(brake[finite]))
    if np.var(y) <= 0:
        zero = np.zeros(d)
        return Sensitivity(population.names, zero, zero, zero, zero, len(y))
    # SALib draws its bootstrap from the global, unseeded generator for a false seed (0 included): seed + 1 keeps
    # every seed's intervals reproducible
    res = sobol_analyze.analyze(problem, y, calc_second_order=False, conf_level=0.95,
                                seed=None if seed is None else int(seed) + 1)
    return Sensitivity(population.names, np.asarray(res["S1"]), np.asarray(res["S1_conf"]),
                       np.asarray(res["ST"]), np.asarray(res["ST_conf"]), len(y))


def sensitivity_chart(sens: Sensitivity, path, title: str = "") -> str:
    """Tornado-style bars of first and total indices with their 95 % intervals, largest total on top (PNG)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    order = np.argsort(sens.total)
    y = np.arange(len(order))
    fig, ax = plt.subplots(figsize=(7, 0.6 * len(order) + 1.6))
    ax.barh(y + 0.2, sens.total[order], 0.4, xerr=sens.total_ci[order], label="total index", color="#c0392b",
            capsize=3)
    ax.barh(y - 0.2, sens.first[order], 0.4, xerr=sens.first_ci[order], label="first-order index",
            color="#2980b9", capsize=3)
    ax.set_yticks(y, [sens.names[i] for i in order])
    ax.set_xlabel("Sobol index of the least brake margin (95 % intervals)")
    ax.set_xlim(0, max(1.0, float(np.max(sens.total + sens.total_ci)) * 1.05))
    ax.set_title(title or "What drives the roll-away margin")
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return str(path)
