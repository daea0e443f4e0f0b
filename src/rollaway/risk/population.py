"""A population of parked cars: a scenario's fixed values plus a ``[vary]`` table, validated from TOML.

Example (``scenarios/populations/fmvss135-production.toml``)::

    description = "FMVSS 135 case with production scatter"
    params = "paper"                 # set name, parameter file or calibrated model file
    grade_pct = 20
    direction = "both"               # "uphill", "downhill", or "both": it must hold facing either way
    occupants = 5
    hand_force_N = 400
    duration_s = 300
    initial_drum_temp_C = 200

    [vary]                           # any scenario number or parameter name (rollaway params)
    mu_drum = { uniform = [0.3, 0.6] }
    hand_force_N = { normal = [400, 35] }

    [[correlation]]                  # Gaussian copula: correlation of the normal scores
    between = ["mu_drum", "initial_drum_temp_C"]
    rho = -0.3

The fixed part is validated as a scenario (:func:`rollaway.hold.scenario.scenario_from_mapping`); the
distributions by :mod:`rollaway.risk.distributions`.  Sampling: independent standard-normal scores u,
correlated by the Cholesky factor of the copula's matrix, each mapped through its marginal.  Unknown
keys, wrong types and impossible distributions are one-line :class:`UserError` naming file and key.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rollaway.errors import UserError, read_toml, suggest
from rollaway.hold import MAX_HAND_FORCE_N, MAX_OCCUPANTS
from rollaway.hold.scenario import MAX_DURATION_S, Scenario, scenario_from_mapping
from rollaway.model.drum_model import DrumModel
from rollaway.model.parameters import SPEC_BY_NAME
from rollaway.risk.distributions import Marginal, check_range, marginal_from_table

DIRECTIONS = ("uphill", "downhill", "both")
SCENARIO_NUMBERS = ("grade_pct", "occupants", "hand_force_N", "duration_s")   # numbers of the scenario itself
# the physical range of every name that may vary (parameters: their validated range, `rollaway params`)
RANGES = {"grade_pct": (-99.999, 100.0), "occupants": (0.0, float(MAX_OCCUPANTS)),
          "hand_force_N": (0.0, MAX_HAND_FORCE_N), "duration_s": (1e-6, MAX_DURATION_S),
          **{s.name: (s.lower, s.upper) for s in SPEC_BY_NAME.values()}}
_OWN_KEYS = ("vary", "correlation")


@dataclass(frozen=True)
class Population:
    """A validated population: fixed scenario, directions, marginals and their copula."""

    name: str
    base: Scenario = field(repr=False)
    directions: tuple[str, ...]
    marginals: tuple[Marginal, ...]
    correlation: np.ndarray = field(repr=False)
    description: str = ""
    source: str | None = None

    @property
    def model(self) -> DrumModel:
        return self.base.model

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.marginals)

    @property
    def dim(self) -> int:
        return len(self.marginals)

    def marginal(self, name: str) -> Marginal:
        for m in self.marginals:
            if m.name == name:
                return m
        raise UserError(f"'{name}' is not varied{suggest(name, self.names)}; varied: {', '.join(self.names)}")

    def fixed(self, name: str) -> float:
        """The fixed value of a scenario number or parameter (its value when not varied)."""
        if name in SCENARIO_NUMBERS:
            return float(getattr(self.base, name))
        if name in SPEC_BY_NAME:
            return float(getattr(self.base.params, name))
        raise UserError(f"'{name}' is no scenario number or parameter{suggest(name, RANGES)}; "
                        f"run 'rollaway params' for the names")

    def values_from_normal(self, u: np.ndarray) -> dict[str, np.ndarray]:
        """Values of every varied name for independent standard-normal scores *u* of shape (n, dim)."""
        u = np.atleast_2d(np.asarray(u, float))
        correlated = self.dim > 1 and np.any(self.correlation != np.eye(self.dim))
        z = u @ np.linalg.cholesky(self.correlation).T if correlated else u
        # far tails (importance sampling visits them) are kept inside the physical range; the file's
        # distributions put at most OUTSIDE_TOLERANCE there (validated)
        return {m.name: np.clip(m.from_normal(z[:, i]), *RANGES[m.name]) for i, m in enumerate(self.marginals)}

    def with_fixed(self, name: str, value: float) -> "Population":
        """This population with one fixed (not varied) value changed, validated like the file's."""
        if name in self.names:
            raise UserError(f"'{name}' is varied; change its distribution (with_marginal) instead of a fixed value")
        self.fixed(name)
        base = self.base.replace(**{name: (int(round(value)) if name == "occupants" else float(value))})
        return dataclasses.replace(self, base=base)

    def with_marginal(self, marginal: Marginal) -> "Population":
        ms = tuple(marginal if m.name == marginal.name else m for m in self.marginals)
        return dataclasses.replace(self, marginals=ms)

    def as_dict(self) -> dict:
        return {"name": self.name, "directions": list(self.directions), "model": self.model.name,
                "vary": {m.name: m.as_dict() for m in self.marginals}}


def _correlation(entries, names: tuple[str, ...], where: str) -> np.ndarray:
    r = np.eye(len(names))
    if entries is None:
        return r
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise UserError(f"{where}: key 'correlation' must be [[correlation]] tables with between = [\"a\", \"b\"] "
                        f"and rho = 0.3")
    for i, e in enumerate(entries):
        key = f"correlation[{i}]"
        for k in e:
            if k not in ("between", "rho"):
                raise UserError(f"{where}: unknown key '{key}.{k}'{suggest(k, ('between', 'rho'))}; "
                                f"valid keys: between, rho")
        pair, rho = e.get("between"), e.get("rho")
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(p, str) for p in pair)):
            raise UserError(f"{where}: key '{key}.between' must name two varied inputs, e.g. "
                            f"between = [\"mu_drum\", \"initial_drum_temp_C\"]; got {pair!r}")
        for p in pair:
            if p not in names:
                raise UserError(f"{where}: key '{key}.between' names '{p}', which is not in [vary]"
                                f"{suggest(p, names)}; varied: {', '.join(names) or 'none'}")
        if pair[0] == pair[1]:
            raise UserError(f"{where}: key '{key}.between' names '{pair[0]}' twice; give two different inputs")
        if isinstance(rho, bool) or not isinstance(rho, (int, float)) or not -1 < rho < 1:
            raise UserError(f"{where}: key '{key}.rho' must be a number strictly between -1 and 1; got {rho!r}")
        a, b = names.index(pair[0]), names.index(pair[1])
        r[a, b] = r[b, a] = float(rho)
    if np.min(np.linalg.eigvalsh(r)) <= 1e-10:
        raise UserError(f"{where}: key 'correlation': the correlations together are impossible (the matrix is "
                        f"not positive definite); weaken some rho")
    return r


def population_from_mapping(data: dict, where: str = "population", base_dir: Path | None = None,
                            params: str | None = None) -> Population:
    """Validate a parsed TOML mapping into a :class:`Population` (*params*: another drum model)."""
    data = dict(data)
    vary = data.pop("vary", {})
    corr = data.pop("correlation", None)
    if not isinstance(vary, dict):
        raise UserError(f"{where}: key 'vary' must be a [vary] table of name = {{ distribution = [...] }}")
    marginals = []
    for name, table in vary.items():
        if name not in RANGES:
            raise UserError(f"{where}: unknown key 'vary.{name}'{suggest(name, RANGES)}; vary a scenario number "
                            f"({', '.join(SCENARIO_NUMBERS)}) or a parameter ('rollaway params' lists them)")
        m = marginal_from_table(name, table, where)
        check_range(m, *RANGES[name], where, whole=name == "occupants")
        marginals.append(m)
    direction = data.get("direction")
    if isinstance(direction, str) and direction not in DIRECTIONS:
        raise UserError(f"{where}: key 'direction' = {direction!r}{suggest(direction, DIRECTIONS)}; "
                        f"use one of: {', '.join(DIRECTIONS)}")
    fixed = dict(data)
    fixed.setdefault("name", Path(where).stem)
    if direction == "both":
        fixed["direction"] = "downhill"
    for m in marginals:                 # a varied scenario number needs no fixed value: its median stands in
        if m.name in SCENARIO_NUMBERS and m.name not in fixed:
            fixed[m.name] = int(round(m.median())) if m.name == "occupants" else m.median()
    try:
        base = scenario_from_mapping(fixed, where=where, base_dir=base_dir, params=params)
    except UserError as exc:
        text = str(exc)
        if "unknown key" in text:
            text = text.rstrip() + ", vary, correlation"
        raise UserError(text) from None
    directions = ("uphill", "downhill") if direction == "both" else (base.direction,)
    names = tuple(m.name for m in marginals)
    return Population(name=base.name, base=base, directions=directions, marginals=tuple(marginals),
                      correlation=_correlation(corr, names, where), description=data.get("description", ""),
                      source=where)


def load_population(path: str | Path, params: str | None = None) -> Population:
    """Read and validate a population TOML file."""
    path = Path(path)
    data = read_toml(path, "population file", "see scenarios/populations/*.toml for examples")
    return population_from_mapping(data, where=str(path), base_dir=path.parent, params=params)
