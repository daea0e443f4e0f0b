"""Residual analysis: structure tests, covariates, excursions (the noise model is in :mod:`.noise`).

The structure tests are calibrated for real bench noise: residuals are standardised by the
noise model and clipped at ±3.5 (Huber-type, so a spike cannot fire a test), and three of
the four tests are self-normalising analyses of variance (they compare the residual's
pattern with its own scatter, not with an assumed σ).
"""
from __future__ import annotations

import math

import numpy as np

from rollaway.bench.measurements import Measurements
from rollaway.bench.noise import CLIP, Noise, clip_square, noise_estimate  # noqa: F401  (re-exported)
from rollaway.scipy_direct import special_functions

special = special_functions()      # scipy.special's ufuncs without its package start (rollaway.scipy_direct)

STRUCTURE_P = 1e-3      # significance of each structure test
CHANNELS = {"torque": ("torque_Nm", "N·m"), "temperature": ("drum_temp_C", "°C")}
MAX_TIME_BINS = 12


def _anova(z: np.ndarray, groups: np.ndarray) -> tuple[float, int, int, float]:
    """F test of group means against zero, error from the within-group scatter: (F, df1, df2, p)."""
    g = np.unique(groups, return_inverse=True)[1]
    ng = int(g.max()) + 1 if g.size else 0
    cnt = np.bincount(g, minlength=ng).astype(float)
    mean = np.bincount(g, z, ng) / np.maximum(cnt, 1)
    between = float(np.sum(cnt * mean ** 2))
    within = float(np.sum((z - mean[g]) ** 2))
    df1, df2 = ng, int(z.size - ng)
    if df2 < 1 or within <= 0:
        return 0.0, df1, max(df2, 1), 1.0
    f = (between / df1) / (within / df2)
    return f, df1, df2, float(special.fdtrc(df1, df2, f))


def time_bins(t: np.ndarray) -> np.ndarray:
    """Sampling times as groups: the distinct times if few, else quantile bins."""
    ut = np.unique(t)
    if len(ut) <= MAX_TIME_BINS:
        return np.searchsorted(ut, t)
    edges = np.unique(np.quantile(t, np.linspace(0, 1, MAX_TIME_BINS + 1)[1:-1]))
    return np.searchsorted(edges, t, side="right")


def structure_tests(data: Measurements, residual: np.ndarray, noise: Noise, k: float = 0,
                    mask: np.ndarray | None = None, sigma: np.ndarray | None = None) -> dict:
    """Tests for structure left in *residual* (measured − model) given the noise model.

    * ``excess_variance``: trimmed mean square of r/σ against the noise's (F test; degrees of
      freedom reduced for heavy tails through the kurtosis, *k* fitted parameters removed);
    * ``autocorrelation``: pooled lag-1 autocorrelation within tests (white noise: ≈ 0);
    * ``test_offsets``: per-test mean residuals against the within-test scatter (ANOVA F);
    * ``time_profile``: mean residual at each sampling time (or time bin) across tests
      against the scatter within (ANOVA F) — a step or a missing transient shows here first.
    Each has a p-value; ``structured`` is True if any p < 0.001.
    """
    m = np.ones(len(residual), bool) if mask is None else mask
    sig = np.full(len(residual), noise.sigma) if sigma is None else np.broadcast_to(np.asarray(sigma, float),
                                                                                    (len(residual),))
    z = np.clip(residual[m] / sig[m], -CLIP, CLIP)
    ti = data.test_index[m]
    n = z.size
    dof_r = max(n - k, 1.0)
    ratio = float(clip_square(residual[m] / sig[m]).sum()) / dof_r
    kurt = float(np.mean(z ** 4) / max(np.mean(z ** 2), 1e-300) ** 2)
    p_var = float(special.fdtrc(dof_r * 2.0 / max(kurt - 1.0, 0.5), max(noise.dof, 1.0), ratio))
    order = np.lexsort((data.time_s[m], ti))
    zs, ts = z[order], ti[order]
    same = ts[1:] == ts[:-1]
    num = float(np.sum((zs[1:] * zs[:-1])[same]))
    den = float(z @ z)
    pairs = int(same.sum())
    rho = num / den if den > 0 else 0.0
    p_ac = float(special.ndtr(-rho * math.sqrt(max(pairs, 1))))
    f_off, d1, d2, p_off = _anova(z, ti)
    f_t, e1, e2, p_time = _anova(z, time_bins(data.time_s[m]))
    tests = {"excess_variance": {"ratio": ratio, "p": p_var}, "autocorrelation": {"lag1": rho, "p": p_ac},
             "test_offsets": {"F": f_off, "df": [d1, d2], "p": p_off},
             "time_profile": {"F": f_t, "df": [e1, e2], "p": p_time}}
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
