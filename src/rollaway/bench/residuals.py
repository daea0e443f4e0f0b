"""Residual analysis: model-free noise estimate, structure tests, covariates, excursions.

The noise level is estimated without the physics: each test gets its own smooth curve,
a cubic in x = e^{−t/τ} (τ the calibrated cooling time constant), fitted by linear least
squares; the pooled residual variance (dof-corrected) is the noise variance.  Any smooth
physical effect within a test, and any difference between tests, is absorbed by these
curves, so what remains is measurement noise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

from rollaway.bench.measurements import Measurements

FLEX_BASIS = 4          # 1, x, x², x³ per test
STRUCTURE_P = 1e-3      # significance of each structure test
CHANNELS = {"torque": ("torque_Nm", "N·m"), "temperature": ("drum_temp_C", "°C")}


@dataclass
class Noise:
    sigma: float
    dof: int

    def as_dict(self):
        return {"sigma": self.sigma, "dof": self.dof}


def noise_estimate(data: Measurements, values: np.ndarray, time_constant_s: float) -> Noise | None:
    """Pooled per-test smooth-curve residual standard deviation of *values* (one channel)."""
    rss, dof = 0.0, 0
    for i in range(data.n_tests):
        rows = data.test_index == i
        n = int(rows.sum())
        if n < FLEX_BASIS + 2:
            continue
        x = np.exp(-data.time_s[rows] / time_constant_s)
        basis = np.vander(x, FLEX_BASIS, increasing=True)
        coef, *_ = np.linalg.lstsq(basis, values[rows], rcond=None)
        r = values[rows] - basis @ coef
        rss += float(r @ r)
        dof += n - FLEX_BASIS
    if dof == 0:
        return None
    return Noise(math.sqrt(rss / dof), dof)


def structure_tests(data: Measurements, residual: np.ndarray, noise: Noise, k: int = 0,
                    mask: np.ndarray | None = None) -> dict:
    """Tests for structure left in *residual* (measured − model) given the noise level.

    * ``excess_variance``: residual variance against the noise variance (F test);
    * ``autocorrelation``: pooled lag-1 autocorrelation within tests (white noise: ≈ 0);
    * ``test_offsets``: per-test mean residuals against σ/√n (χ² test).
    Each has a p-value; ``structured`` is True if any p < 0.001.
    """
    m = np.ones(len(residual), bool) if mask is None else mask
    r, ti = residual[m], data.test_index[m]
    n = r.size
    s2 = float(r @ r) / max(n - k, 1)
    f = s2 / noise.sigma ** 2
    p_var = float(stats.f.sf(f, max(n - k, 1), noise.dof))
    num = den = 0.0
    pairs = 0
    chi2 = 0.0
    groups = 0
    for i in np.unique(ti):
        ri = r[ti == i]
        num += float(ri[1:] @ ri[:-1])
        den += float(ri @ ri)
        pairs += ri.size - 1
        chi2 += ri.size * float(ri.mean()) ** 2 / noise.sigma ** 2
        groups += 1
    rho = num / den if den > 0 else 0.0
    p_ac = float(stats.norm.sf(rho * math.sqrt(max(pairs, 1))))
    p_off = float(stats.chi2.sf(chi2, groups))
    tests = {"excess_variance": {"ratio": f, "p": p_var}, "autocorrelation": {"lag1": rho, "p": p_ac},
             "test_offsets": {"chi2": chi2, "df": groups, "p": p_off}}
    tests["structured"] = any(t["p"] < STRUCTURE_P for t in tests.values() if isinstance(t, dict))
    return tests


def covariates(data: Measurements, temp_C: np.ndarray) -> dict[str, np.ndarray]:
    return {"time": data.time_s, "temperature": temp_C, "hand force": data.hand_force_N,
            "direction": data.sign}


def _groups(name: str, x: np.ndarray) -> np.ndarray:
    """Bin labels for a covariate: its distinct values, or quintiles if there are many."""
    u = np.unique(x)
    if len(u) <= 8 or name in ("hand force", "direction"):
        return np.searchsorted(u, x)
    edges = np.quantile(x, [0.2, 0.4, 0.6, 0.8])
    return np.searchsorted(edges, x)


def association(data: Measurements, residual: np.ndarray, temp_C: np.ndarray,
                mask: np.ndarray | None = None) -> list[tuple[str, float]]:
    """Share of the residual's variance explained by binned means of each covariate, largest first."""
    m = np.ones(len(residual), bool) if mask is None else mask
    r = residual[m]
    tot = float(((r - r.mean()) ** 2).sum()) or 1.0
    out = []
    for name, x in covariates(data, temp_C).items():
        g = _groups(name, x[m])
        explained = sum(float((g == k).sum()) * (float(r[g == k].mean()) - r.mean()) ** 2 for k in np.unique(g))
        out.append((name, explained / tot))
    return sorted(out, key=lambda t: -t[1])


def trend_words(data: Measurements, residual: np.ndarray, temp_C: np.ndarray, name: str,
                mask: np.ndarray | None = None) -> str:
    """E.g. 'rises with time' / 'higher facing downhill' for the strongest covariate."""
    m = np.ones(len(residual), bool) if mask is None else mask
    x = covariates(data, temp_C)[name][m]
    r = residual[m]
    if name == "direction":
        d, u = r[x > 0].mean() if np.any(x > 0) else 0.0, r[x < 0].mean() if np.any(x < 0) else 0.0
        return f"is {'higher' if d > u else 'lower'} facing downhill ({d:+.3g}) than uphill ({u:+.3g})"
    if np.ptp(x) == 0:
        return "constant"
    c = float(np.corrcoef(x, r)[0, 1]) if np.std(r) > 0 else 0.0
    return f"{'rises' if c > 0 else 'falls'} with {name} (correlation {c:+.2f})"


def excursions(data: Measurements, residual: np.ndarray, sigma: float, band: float = 2.5,
               mask: np.ndarray | None = None) -> list[dict]:
    """Runs of samples where |residual| > band·σ, per test: test, from/to time, sign, worst value."""
    m = np.ones(len(residual), bool) if mask is None else mask
    out = []
    for i, tid in enumerate(data.tests):
        rows = np.flatnonzero((data.test_index == i) & m)
        rows = rows[np.argsort(data.time_s[rows])]
        out_of = np.abs(residual[rows]) > band * sigma
        k = 0
        while k < len(rows):
            if not out_of[k]:
                k += 1
                continue
            j = k
            sgn = np.sign(residual[rows[k]])
            while j + 1 < len(rows) and out_of[j + 1] and np.sign(residual[rows[j + 1]]) == sgn:
                j += 1
            seg = rows[k:j + 1]
            worst = seg[np.argmax(np.abs(residual[seg]))]
            out.append({"test_id": tid, "from_s": float(data.time_s[seg[0]]), "to_s": float(data.time_s[seg[-1]]),
                        "samples": len(seg), "sign": "above" if sgn > 0 else "below",
                        "worst": float(residual[worst]), "worst_at_s": float(data.time_s[worst])})
            k = j + 1
    return out
