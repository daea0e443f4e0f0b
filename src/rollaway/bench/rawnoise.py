"""Noise of a high-rate bench log: at the raw rate, and of the window means the reduction keeps.

* :func:`raw_noise` — σ of each channel from the degree-1 pseudo-residuals of consecutive samples
  (summed per window by :mod:`rollaway.bench.reduction`); torque as σ² = a² + (b·M)² fitted to the
  windows' mean squares (weighted least squares, non-negative).  The full mean square, not a trimmed
  one: heavy tails do enter the variance of a mean.
* :func:`dispersion` — whether σ/√n is the standard error of a window mean: pseudo-residuals of the
  window means themselves (a combination of 5 consecutive windows that cancels any cubic in time; over
  a few windows the signal is far smoother than that) against their predicted variance.  Noise
  correlated between samples (a DAQ filter) makes them larger than σ/√n says, and the median ratio
  over the log (robust to a step or a spike) is the factor by which σ/√n must be widened.  Applied
  only where significant (F test, p < 0.001).
* :func:`window_noise` — the noise of a window mean, for comparisons of residuals with "the noise".
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from rollaway.bench.noise import Noise, sample_sigma
from rollaway.scipy_direct import nnls, special_functions

special = special_functions()      # scipy.special's ufuncs without its package start (rollaway.scipy_direct)

# per-window sums, as in rollaway.bench.reduction: n, Σt, ΣT, ΣM, Σambient, n_e, Σe_T², Σe_M²
N, ST, STEMP, SQ, SAMB, NE, E2T, E2Q = range(8)
# pseudo-residuals of overlapping 3-sample windows share samples: n_e of them carry about n_e/1.94
# independent squares for Gaussian noise (lag-1, lag-2 correlations −2/3, 1/6 on a regular grid)
OVERLAP = 1.0 + 2.0 * ((2.0 / 3.0) ** 2 + (1.0 / 6.0) ** 2)
DISPERSION_P = 1e-3
ORDER = 4               # the dispersion check cancels polynomials of degree < 4 across consecutive windows


def raw_noise(sums: list[np.ndarray], e4: list[np.ndarray]) -> tuple[Noise, Noise]:
    """Raw-rate noise of both channels from the per-window pseudo-residual sums (torque: absolute + relative)."""
    s = np.concatenate(sums)
    s = s[s[:, NE] > 0]
    ne = s[:, NE]
    total = float(ne.sum())
    e4 = np.sum(e4, axis=0)
    kurt_t = e4[0] * total / max(float(s[:, E2T].sum()) ** 2, 1e-300)
    kurt_q = e4[1] * total / max(float(s[:, E2Q].sum()) ** 2, 1e-300)
    note = f"estimated at the raw rate ({int(total):,} pseudo-residuals of consecutive samples)"
    a_t = math.sqrt(float(s[:, E2T].sum()) / total)
    nt = Noise(a_t, _dof(total, kurt_t), a_t, 0.0, 1, True, "data", note)
    level = s[:, SQ] / np.maximum(s[:, N], 1)
    mean_e2 = s[:, E2Q] / ne
    a2, b2 = float(s[:, E2Q].sum()) / total, 0.0
    design = np.column_stack([np.ones_like(level), level ** 2])
    for _ in range(4):      # weighted least squares of the mean squares (variance ∝ σ⁴/n_e)
        wgt = np.sqrt(ne) / np.maximum(a2 + b2 * level ** 2, 1e-300)
        a2, b2 = nnls(design * wgt[:, None], mean_e2 * wgt)
        if a2 + b2 * float(np.mean(level ** 2)) <= 0:
            a2, b2 = float(s[:, E2Q].sum()) / total, 0.0
            break
    sig = math.sqrt(float(np.sum(ne * (a2 + b2 * level ** 2)) / total))
    nq = Noise(sig, _dof(total, kurt_q), math.sqrt(max(a2, 0.0)), math.sqrt(max(b2, 0.0)), 1, True, "data", note)
    return nq, nt


def _dof(n_e: float, kurtosis: float) -> float:
    return n_e / OVERLAP * 2.0 / max(kurtosis - 1.0, 0.5)


def dispersion(windows, nq: Noise, nt: Noise) -> tuple[float, float]:
    """Factors (torque, temperature) ≥ 1 by which σ/√n understates a window mean's standard error.

    *windows*: per test ``(t, T, M, n)`` of its window means.  Every run of ORDER + 1 consecutive full
    windows has one combination that cancels any polynomial of degree < ORDER in time; with independent
    noise its square over its predicted variance Σc²σ²/n is χ²₁."""
    out = []
    for col, noise in ((2, nq), (1, nt)):
        z2 = []
        for win in windows:
            t, y, n = win[0], win[col], win[3]
            full = n >= 0.5 * np.median(n)
            t, y, n = t[full], y[full], n[full]
            m = ORDER + 1
            if len(t) < m:
                continue
            idx = np.arange(len(t) - m + 1)[:, None] + np.arange(m)
            x = t[idx]
            x = (x - x.mean(axis=1, keepdims=True)) / np.maximum(np.ptp(x, axis=1, keepdims=True), 1e-300)
            diff = x[:, :, None] - x[:, None, :]
            diff[:, np.arange(m), np.arange(m)] = 1.0
            c = 1.0 / np.prod(diff, axis=2)
            c /= np.linalg.norm(c, axis=1, keepdims=True)
            e = np.einsum("ij,ij->i", c, y[idx])
            v = np.einsum("ij,ij->i", c * c, (noise.at(y) ** 2 / n)[idx])
            z2.append(e * e / np.maximum(v, 1e-300))
        if not z2:
            out.append(1.0)
            continue
        z2 = np.concatenate(z2)
        kappa2 = float(np.median(z2)) / float(special.chdtri(1, 0.5))       # median-unbiased for χ²₁
        dof = z2.size / (2.0 * ORDER)          # overlapping combinations, the median's efficiency: conservative
        p = float(special.fdtrc(dof, max(noise.dof, 1.0), kappa2))
        out.append(math.sqrt(kappa2) if kappa2 > 1.0 and p < DISPERSION_P else 1.0)
    return out[0], out[1]


def window_noise(noise: Noise, data, level: np.ndarray, mask: np.ndarray) -> Noise:
    """The noise of a window mean of reduced *data* (RMS of σ(level)/√n over the *mask* rows), for comparisons
    of residuals of window means with "the noise"."""
    sig = float(np.sqrt(np.mean(sample_sigma(noise, data, level)[mask] ** 2)))
    return replace(noise, sigma=sig, note=(noise.note + "; " if noise.note else "") +
                   f"σ of a window mean (raw-rate σ {noise.sigma:.3g} over √samples)")


