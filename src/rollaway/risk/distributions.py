"""One varied input's distribution, validated from its TOML table, as a map from standard-normal space.

Each ``[vary]`` entry is a marginal distribution of :mod:`scipy.stats` (why scipy and not a hand-written
sampler: its quantile functions are accurate far into the tails, which the rare-event estimators need)::

    mu_drum = { uniform = [0.3, 0.6] }                       # lower, upper
    hand_force_N = { normal = [400, 35], truncate = [150, 600] }   # mean, sd; optional truncation
    heat_transfer_W_m2K = { lognormal = [40, 0.15] }         # median, sd of the log
    initial_drum_temp_C = { triangular = [27, 120, 300] }    # lower, mode, upper
    occupants = { choice = [0, 1, 2, 5], weights = [0.3, 0.4, 0.2, 0.1] }   # weights default to equal

Every marginal is used through :meth:`Marginal.from_normal`: a standard-normal score z is mapped to
the value with the same probability, ``F⁻¹(Φ(z))`` (the isoprobabilistic transform of reliability
analysis; the upper tail through the survival function so 1-ppm quantiles keep their digits).  The
estimators (:mod:`rollaway.risk.estimators`) work in that standard-normal space.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special, stats

from rollaway.errors import UserError, suggest

KINDS = {"uniform": 2, "normal": 2, "lognormal": 2, "triangular": 3, "choice": None}
OPTIONS = ("weights", "truncate")
OUTSIDE_TOLERANCE = 1e-9     # probability a distribution may put outside the physical range [assumed]


@dataclass(frozen=True)
class Marginal:
    """A validated marginal distribution of one varied input."""

    name: str
    kind: str
    args: tuple[float, ...]
    weights: tuple[float, ...] | None = None       # choice only, normalised
    truncate: tuple[float, float] | None = None

    @property
    def discrete(self) -> bool:
        return self.kind == "choice"

    def _frozen(self):
        a = self.args
        if self.kind == "uniform":
            return stats.uniform(loc=a[0], scale=a[1] - a[0])
        if self.kind == "normal":
            return stats.norm(loc=a[0], scale=a[1])
        if self.kind == "lognormal":
            return stats.lognorm(s=a[1], scale=a[0])
        lo, mode, hi = a
        return stats.triang(c=(mode - lo) / (hi - lo), loc=lo, scale=hi - lo)

    def _bounds_cdf(self) -> tuple[float, float]:
        """(F(lower), S(upper)): the probability cut off below and above by the truncation."""
        if self.truncate is None or self.discrete:
            return 0.0, 0.0
        d = self._frozen()
        return float(d.cdf(self.truncate[0])), float(d.sf(self.truncate[1]))

    def from_normal(self, z) -> np.ndarray:
        """Values with the probabilities of standard-normal scores *z* (vectorised)."""
        z = np.asarray(z, float)
        if self.discrete:
            vals = np.asarray(self.args)
            cum = np.cumsum(self.weights)[:-1]
            return vals[np.searchsorted(cum, special.ndtr(z), side="right")]
        if self.truncate is None and self.kind in ("normal", "lognormal", "uniform"):   # exact, fast
            a = self.args
            if self.kind == "normal":
                return a[0] + a[1] * z
            if self.kind == "lognormal":
                return a[0] * np.exp(a[1] * z)
            return a[0] + (a[1] - a[0]) * special.ndtr(z)
        if self.truncate is None and self.kind == "triangular":      # the inverse CDF in closed form
            lo, mode, hi = self.args
            c = (mode - lo) / (hi - lo)
            p, s = special.ndtr(z), special.ndtr(-z)
            return np.where(p <= c, lo + np.sqrt(p * (hi - lo) * (mode - lo)),
                            hi - np.sqrt(s * (hi - lo) * (hi - mode)))
        d = self._frozen()
        cut_lo, cut_hi = self._bounds_cdf()
        keep = 1.0 - cut_lo - cut_hi
        lower = z < 0
        out = np.empty(z.shape)
        out[lower] = d.ppf(cut_lo + keep * special.ndtr(z[lower]))       # lower tail through the CDF
        out[~lower] = d.isf(cut_hi + keep * special.ndtr(-z[~lower]))    # upper tail through the survival
        if self.truncate is not None:
            out = np.clip(out, *self.truncate)
        return out

    def median(self) -> float:
        return float(self.from_normal(0.0))

    def support(self) -> tuple[float, float]:
        """(least, greatest) value the distribution can take."""
        if self.discrete:
            vals = [v for v, w in zip(self.args, self.weights) if w > 0]
            return min(vals), max(vals)
        d = self._frozen()
        lo, hi = d.support()
        if self.truncate is not None:
            lo, hi = max(lo, self.truncate[0]), min(hi, self.truncate[1])
        return float(lo), float(hi)

    def mass_outside(self, lower: float, upper: float) -> float:
        """Probability of a value below *lower* or above *upper*."""
        if self.discrete:
            return float(sum(w for v, w in zip(self.args, self.weights) if not lower <= v <= upper))
        d = self._frozen()
        cut_lo, cut_hi = self._bounds_cdf()
        keep = 1.0 - cut_lo - cut_hi
        below = max(float(d.cdf(lower)) - cut_lo, 0.0) / keep
        above = max(float(d.sf(upper)) - cut_hi, 0.0) / keep
        return below + above

    def with_bound(self, side: str, value: float) -> "Marginal":
        """The same distribution truncated at a new lower or upper spec limit (*side* ``"lower"``/``"upper"``)."""
        lo, hi = self.truncate or (-math.inf, math.inf)
        new = (value, hi) if side == "lower" else (lo, value)
        if self.discrete:
            w = [wi if new[0] <= v <= new[1] else 0.0 for v, wi in zip(self.args, self.weights)]
            total = sum(w)
            if total <= 0:
                raise UserError(f"{self.name}: no choice is left within the spec limit {value:g}")
            return Marginal(self.name, self.kind, self.args, tuple(x / total for x in w), None)
        return Marginal(self.name, self.kind, self.args, None, new)

    def shifted_to(self, median: float) -> "Marginal":
        """The same scatter moved so its median is *median* (a nominal value changed, tolerances kept):
        added for uniform, normal, triangular and choice, a factor for the lognormal."""
        if self.kind == "lognormal":
            if median <= 0:
                raise UserError(f"{self.name}: a lognormal median must be > 0, got {median:g}")
            return Marginal(self.name, self.kind, (median, self.args[1]), self.weights, self.truncate)
        delta = median - self.median()
        trunc = None if self.truncate is None else (self.truncate[0] + delta, self.truncate[1] + delta)
        args = tuple(a + delta for a in self.args) if self.kind != "normal" else (self.args[0] + delta, self.args[1])
        return Marginal(self.name, self.kind, args, self.weights, trunc)

    def as_dict(self) -> dict:
        out = {self.kind: list(self.args)}
        if self.weights is not None:
            out["weights"] = list(self.weights)
        if self.truncate is not None:
            out["truncate"] = list(self.truncate)
        return out


def _numbers(value, where: str, key: str, count: int | None) -> tuple[float, ...]:
    ok = isinstance(value, list) and value and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                   for v in value)
    if not ok or (count is not None and len(value) != count):
        n = f"{count} numbers" if count else "a list of numbers"
        raise UserError(f"{where}: key '{key}' must be {n} in brackets, e.g. {key} = {_EXAMPLES[key.split('.')[-1]]}; "
                        f"got {value!r}")
    if not all(math.isfinite(v) for v in value) and not key.endswith("truncate"):
        raise UserError(f"{where}: key '{key}' = {value!r} has a value that is not finite; give finite numbers")
    return tuple(float(v) for v in value)


_EXAMPLES = {"uniform": "[0.3, 0.6]", "normal": "[400, 35]", "lognormal": "[40, 0.15]",
             "triangular": "[27, 120, 300]", "choice": "[0, 1, 2]", "weights": "[0.5, 0.3, 0.2]",
             "truncate": "[150, 600]"}


def marginal_from_table(name: str, table, where: str) -> Marginal:
    """Validate one ``[vary]`` entry (``{ normal = [400, 35] }``) into a :class:`Marginal`."""
    key = f"vary.{name}"
    if not isinstance(table, dict):
        raise UserError(f"{where}: key '{key}' must be an inline table naming a distribution, e.g. "
                        f"{name} = {{ uniform = [0.3, 0.6] }}; got {table!r}")
    for k in table:
        if k not in KINDS and k not in OPTIONS:
            raise UserError(f"{where}: unknown key '{key}.{k}'{suggest(k, (*KINDS, *OPTIONS))}; a distribution "
                            f"is one of {', '.join(KINDS)} (options: {', '.join(OPTIONS)})")
    kinds = [k for k in table if k in KINDS]
    if len(kinds) != 1:
        raise UserError(f"{where}: key '{key}' must name exactly one distribution ({', '.join(KINDS)}); "
                        f"got {', '.join(kinds) or 'none'}")
    kind = kinds[0]
    args = _numbers(table[kind], where, f"{key}.{kind}", KINDS[kind])
    bad = None
    if kind == "uniform" and not args[0] < args[1]:
        bad = "the lower end must be below the upper end"
    elif kind == "normal" and not args[1] > 0:
        bad = "the standard deviation (second number) must be > 0"
    elif kind == "lognormal" and not (args[0] > 0 and args[1] > 0):
        bad = "the median and the sd of the log must both be > 0"
    elif kind == "triangular" and not (args[0] <= args[1] <= args[2] and args[0] < args[2]):
        bad = "the numbers must be lower ≤ mode ≤ upper with lower < upper"
    if bad:
        raise UserError(f"{where}: key '{key}.{kind}' = {list(args)} is impossible: {bad}")
    weights = None
    if "weights" in table:
        if kind != "choice":
            raise UserError(f"{where}: key '{key}.weights' belongs to a choice; remove it or use choice = [...]")
        w = _numbers(table["weights"], where, f"{key}.weights", len(args))
        if min(w) < 0 or sum(w) <= 0:
            raise UserError(f"{where}: key '{key}.weights' = {list(w)} must be ≥ 0 with a positive sum")
        weights = tuple(x / sum(w) for x in w)
    elif kind == "choice":
        weights = tuple(1.0 / len(args) for _ in args)
    trunc = None
    if "truncate" in table:
        if kind == "choice":
            raise UserError(f"{where}: key '{key}.truncate' does not apply to a choice; list only allowed values")
        lo, hi = _numbers(table["truncate"], where, f"{key}.truncate", 2)
        if not lo < hi:
            raise UserError(f"{where}: key '{key}.truncate' = [{lo:g}, {hi:g}] must have lower < upper")
        trunc = (lo, hi)
    m = Marginal(name, kind, args, weights, trunc)
    if trunc is not None:
        cut_lo, cut_hi = m._bounds_cdf()
        if 1.0 - cut_lo - cut_hi < 1e-12:
            raise UserError(f"{where}: key '{key}.truncate' = [{lo:g}, {hi:g}] leaves no probability of the "
                            f"{kind} distribution; widen it")
    return m


def check_range(m: Marginal, lower: float, upper: float, where: str, whole: bool = False) -> None:
    """A one-line error when *m* puts probability outside the physical range [lower, upper]."""
    key = f"vary.{m.name}"
    if whole and not m.discrete:
        raise UserError(f"{where}: key '{key}' is a whole number; use choice = [...] with weights")
    if whole and any(v != round(v) for v in m.args):
        raise UserError(f"{where}: key '{key}.choice' = {list(m.args)} must list whole numbers")
    out = m.mass_outside(lower, upper)
    if out > OUTSIDE_TOLERANCE:
        raise UserError(f"{where}: key '{key}' puts {out:.3g} of its probability outside the physical range "
                        f"[{lower:g}, {upper:g}]; add truncate = [{max(lower, m.support()[0]):g}, "
                        f"{min(upper, m.support()[1]):g}] or narrow it")
