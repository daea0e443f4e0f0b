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

from rollaway.identify.measurements import Measurements

FLEX_BASIS = 4          # 1, x, x², x³ per test
STRUCTURE_P = 1e-3      # significance of each structure test
CHANNELS = {"torque": ("torque_Nm", "N·m"), "temperature": ("drum_temp_C", "°C")}


@dataclass
class Noise:
    """Noise model σ_i = √(a² + (b·y_i)²): absolute part a, relative part b (of the signal level y)."""

    sigma: float            # pooled (root-mean-square) σ over the samples
    dof: int
    absolute: float = 0.0
    relative: float = 0.0

    def at(self, level) -> np.ndarray:
        return np.sqrt(self.absolute ** 2 + (self.relative * np.asarray(level, float)) ** 2)

    def as_dict(self):
        return {"sigma": self.sigma, "dof": self.dof, "absolute": self.absolute, "relative": self.relative}


def noise_estimate(data: Measurements, values: np.ndarray, time_constant_s: float,
                   relative: bool = False) -> Noise | None:
    """Noise of one channel from per-test smooth curves (no physics).

    With *relative*, the per-test variances s_k² are regressed (non-negative least squares,
    weighted by their dof) on a² + b²·⟨y²⟩_k, so noise proportional to the signal (a torque
    σ of 1–2 %) is recognised; otherwise σ is one pooled constant.
    """
    rss_k, dof_k, lev_k = [], [], []
    for i in range(data.n_tests):
        rows = data.test_index == i
        n = int(rows.sum())
        if n < FLEX_BASIS + 2:
            continue
        x = np.exp(-data.time_s[rows] / time_constant_s)
        basis = np.vander(x, FLEX_BASIS, increasing=True)
        coef, *_ = np.linalg.lstsq(basis, values[rows], rcond=None)
        r = values[rows] - basis @ coef
        rss_k.append(float(r @ r))
        dof_k.append(n - FLEX_BASIS)
        lev_k.append(float(np.mean((basis @ coef) ** 2)))
    dof = int(sum(dof_k))
    if dof == 0:
        return None
    pooled = math.sqrt(sum(rss_k) / dof)
    if not relative or len(rss_k) < 3:
        return Noise(pooled, dof, pooled, 0.0)
    from scipy.optimize import nnls
    d = np.array(dof_k, float)
    s2 = np.array(rss_k) / d
    design = np.column_stack([np.ones_like(s2), np.array(lev_k)])
    fitted = np.full_like(s2, float(np.sum(d * s2) / np.sum(d)))
    for _ in range(3):    # iteratively reweighted: var(s²) ∝ σ⁴/dof, σ from the current fit (not the noisy s²)
        w = np.sqrt(d) / np.maximum(fitted, 1e-30)
        (a2, b2), _ = nnls(design * w[:, None], s2 * w)
        fitted = np.maximum(design @ np.array([a2, b2]), 1e-30)
    if a2 + b2 <= 0:
        return Noise(pooled, dof, pooled, 0.0)
    sig = np.sqrt(a2 + b2 * np.array(lev_k))
    return Noise(float(np.sqrt(np.sum(d * sig ** 2) / dof)), dof, math.sqrt(a2), math.sqrt(b2))


def structure_tests(data: Measurements, residual: np.ndarray, noise: Noise, k: int = 0,
                    mask: np.ndarray | None = None, sigma: np.ndarray | None = None) -> dict:
    """Tests for structure left in *residual* (measured − model) given the noise level.

    * ``excess_variance``: residual variance against the noise variance (F test);
    * ``autocorrelation``: pooled lag-1 autocorrelation within tests (white noise: ≈ 0);
    * ``test_offsets``: per-test mean residuals against σ/√n (χ² test);
    * ``time_profile``: mean residual at each sampling time across tests (χ² test) — a shared
      time-shaped misfit (a step, a missing transient) shows here first.
    Each has a p-value; ``structured`` is True if any p < 0.001.
    """
    m = np.ones(len(residual), bool) if mask is None else mask
    sig = np.full(len(residual), noise.sigma) if sigma is None else np.asarray(sigma, float)
    r, ti = residual[m] / sig[m], data.test_index[m]     # standardised residuals
    n = r.size
    s2 = float(r @ r) / max(n - k, 1)
    f = s2
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
        chi2 += ri.size * float(ri.mean()) ** 2
        groups += 1
    rho = num / den if den > 0 else 0.0
    t = data.time_s[m]
    ut = np.unique(t)
    bins = np.searchsorted(ut, t) if len(ut) <= 30 else np.searchsorted(np.quantile(t, np.linspace(.1, .9, 9)), t)
    chi2_t = sum(float((bins == b).sum()) * float(r[bins == b].mean()) ** 2 for b in np.unique(bins))
    p_time = float(stats.chi2.sf(chi2_t, len(np.unique(bins))))
    p_ac = float(stats.norm.sf(rho * math.sqrt(max(pairs, 1))))
    p_off = float(stats.chi2.sf(chi2, groups))
    tests = {"excess_variance": {"ratio": f, "p": p_var}, "autocorrelation": {"lag1": rho, "p": p_ac},
             "test_offsets": {"chi2": chi2, "df": groups, "p": p_off},
             "time_profile": {"chi2": chi2_t, "df": int(len(np.unique(bins))), "p": p_time}}
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
