"""Measurement noise of a channel without the physics: local-polynomial pseudo-residuals.

Within each test, every run of p + 2 consecutive samples has one linear combination
``e = Σ c_j·y_j`` (‖c‖ = 1) that is exactly zero for any polynomial of degree ≤ p in the
local coordinate x = e^{−t/τ} (the drum's cooling coordinate, in which a cooling test is a
straight line).  For pure noise, Var(e) = σ² whatever the noise distribution, on any
sampling grid (Gasser, Sroka & Jennen-Steinmetz 1986, Biometrika 73(3); Hall, Kay &
Titterington 1990).  The degree is raised (p = 1, 2, 3, 4) while the next degree gives a
significantly smaller variance (the signal's curvature between samples leaks in); if the
highest degree the data allow still decreases, or too few combinations remain, the
estimate is flagged unreliable (an upper bound) and the caller must say so.

Robust to outliers and steps: σ is a trimmed scale (mean of e² over |e| < 3.5σ, iterated
from the MAD, Gaussian-consistent), so a spike or a step touches only the few combinations
that straddle it and those get no weight.  A mean of many samples feels the noise's whole
variance, tails included: ``mean_factor`` is the root mean square of e/σ over |e| < 10σ (≥ 1;
about 1.09 for Student-t noise with 4 degrees of freedom), the factor on σ/√n of a mean.  With ``relative``, σ_i² = a² +
(b·y_i)² is fitted to the clipped e² (iteratively reweighted non-negative least squares),
so a torque noise proportional to the signal is recognised.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rollaway.errors import UserError
from rollaway.scipy_direct import nnls, special_functions

special = special_functions()      # scipy.special's ufuncs without its package start (rollaway.scipy_direct)

CLIP = 3.5                 # values beyond ±3.5 σ are outliers (a spike, the samples around a step)
# E[Z²·1(|Z| < c)] for standard normal Z: keeps the trimmed mean square Gaussian-consistent
CLIP_GAUSS = float(1 - 2 * (CLIP * (math.exp(-0.5 * CLIP * CLIP) / math.sqrt(2 * math.pi)) + special.ndtr(-CLIP)))
FAR = 10.0                 # beyond ±10 σ a value is a spike or a step, not the noise's tail
MAX_DEGREE = 4
MIN_DOF = 10               # fewer effective combinations: the estimate is not reliable
MAX_WINDOWS = 60_000       # a denser log is estimated on this many windows evenly spread over its tests (σ to ~0.4 %)
CURVATURE_P = 0.01         # significance of "the next degree is smaller"


def clip_square(z: np.ndarray) -> np.ndarray:
    """z²·1(|z| < c) / E[Z²·1(|Z| < c)]: a Gaussian-consistent square that gives outliers no weight."""
    z2 = np.square(z)
    return np.where(z2 < CLIP ** 2, z2, 0.0) / CLIP_GAUSS


@dataclass
class Noise:
    """Noise model σ_i = √(a² + (b·y_i)²): absolute part a, relative part b (of the signal level y)."""

    sigma: float            # pooled (root-mean-square) σ over the samples
    dof: float              # effective degrees of freedom of σ² (overlap and tails accounted)
    absolute: float = 0.0
    relative: float = 0.0
    degree: int | None = None       # local polynomial degree used
    reliable: bool = True
    source: str = "data"            # "data" (pseudo-residuals) or "instrument" (given by the user)
    note: str = ""
    mean_factor: float = 1.0        # σ of a mean of n consecutive samples is mean_factor·σ/√n (correlated noise)

    def at(self, level) -> np.ndarray:
        return np.sqrt(self.absolute ** 2 + (self.relative * np.asarray(level, float)) ** 2)

    def as_dict(self):
        return {"sigma": self.sigma, "dof": self.dof, "absolute": self.absolute, "relative": self.relative,
                "degree": self.degree, "reliable": self.reliable, "source": self.source, "note": self.note,
                "mean_factor": self.mean_factor}

    @classmethod
    def instrument(cls, sigma: float, relative: float = 0.0) -> "Noise":
        return cls(float(sigma), 1e6, float(sigma), float(relative), None, True, "instrument",
                   "given by the user (instrument figure)")


def _windows(test_index: np.ndarray, time_s: np.ndarray, m: int, order: np.ndarray | None = None,
             max_windows: int | None = None) -> np.ndarray:
    """Row indices (windows × m) of every run of m consecutive samples within one test (*order*: the rows sorted by
    test, then time, if known); with more than *max_windows* of them, every k-th (evenly spread, not overlapping)."""
    order = np.lexsort((time_s, test_index)) if order is None else order
    ti = test_index[order]
    n = len(order)
    if n < m:
        return np.zeros((0, m), int)
    starts = np.arange(n - m + 1)
    if max_windows and starts.size > max_windows:
        starts = starts[::max(-(-starts.size // max_windows), m)]
    ok = ti[starts] == ti[starts + m - 1]
    return order[starts[ok][:, None] + np.arange(m)]


def pseudo_residuals(time_s, values, test_index, time_constant_s: float, degree: int, order=None,
                     max_windows: int | None = None):
    """(e, level, window rows, coefficients): one pseudo-residual per window of degree + 2 samples (at most
    *max_windows*: :func:`_windows`)."""
    m = degree + 2
    w = _windows(np.asarray(test_index), np.asarray(time_s, float), m, order, max_windows)
    if len(w) == 0:
        return np.zeros(0), np.zeros(0), w, np.zeros((0, m))
    t = np.asarray(time_s, float)[w]
    x = np.exp(-t / time_constant_s)
    span = np.ptp(x, axis=1, keepdims=True)
    gap = np.min(np.diff(np.sort(x, axis=1), axis=1), axis=1)   # two samples at one x (exp underflows to 0)
    use_t = (span[:, 0] <= 1e-9 * np.max(np.abs(x), axis=1)) | (gap <= 1e-9 * span[:, 0])  # degenerate: use time
    x = np.where(use_t[:, None], t, x)
    x = (x - x.mean(axis=1, keepdims=True)) / np.maximum(np.ptp(x, axis=1, keepdims=True), 1e-300)
    # the (p+1)-th divided difference over p+2 points annihilates every polynomial of degree ≤ p:
    # c_j ∝ 1/Π_{i≠j}(x_j − x_i); normalised to ‖c‖ = 1
    diff = x[:, :, None] - x[:, None, :]
    diff[:, np.arange(m), np.arange(m)] = 1.0
    c = 1.0 / np.prod(diff, axis=2)
    c /= np.linalg.norm(c, axis=1, keepdims=True)
    y = np.asarray(values, float)[w]
    return np.einsum("ij,ij->i", c, y), np.abs(y).mean(axis=1), w, c


def _effective_dof(w: np.ndarray, c: np.ndarray, kurtosis: float) -> float:
    """n²/Σ_{w,w'} (c_w·c_w')² for Gaussian noise (overlapping windows share samples), scaled for tails."""
    n, m = w.shape
    if n == 0:
        return 0.0
    total = float(n)                       # w = w'
    for lag in range(1, m):                # windows overlapping by m − lag samples (same test, adjacent)
        same = np.all(w[lag:, :m - lag] == w[:-lag, lag:], axis=1)
        dots = np.einsum("ij,ij->i", c[lag:, :m - lag], c[:-lag, lag:])
        total += 2.0 * float(np.sum(np.where(same, dots ** 2, 0.0)))
    return n * n / total * 2.0 / max(kurtosis - 1.0, 0.5)


def _scale(e: np.ndarray, level: np.ndarray, relative: bool) -> tuple[float, float]:
    """Huber-type absolute (and relative) scale of the pseudo-residuals."""
    s = 1.4826 * float(np.median(np.abs(e))) or float(np.sqrt(np.mean(e ** 2))) or 1e-12
    a2, b2 = s * s, 0.0
    design = np.column_stack([np.ones_like(level), level ** 2])
    for _ in range(6):
        sig2 = np.maximum(a2 + b2 * level ** 2, 1e-300)
        e2 = clip_square(e / np.sqrt(sig2)) * sig2
        if relative:
            wgt = 1.0 / sig2
            a2, b2 = nnls(design * wgt[:, None], e2 * wgt)
            if a2 + b2 * float(np.mean(level ** 2)) <= 0:
                a2, b2 = float(np.mean(e2)), 0.0
        else:
            a2 = float(np.mean(e2))
    return math.sqrt(max(a2, 0.0)), math.sqrt(max(b2, 0.0))


def raw_rate_noise(data, values) -> Noise | None:
    """The noise measured at the raw rate when *data* is a reduced log (:mod:`rollaway.bench.reduction`)
    and *values* one of its channels; None otherwise (its rows are window means: their scatter is not the noise)."""
    red = getattr(data, "reduction", None)
    if red is None or getattr(red, "noise_torque", None) is None:
        return None
    return red.noise_torque if values is data.torque_Nm else red.noise_temp if values is data.drum_temp_C else None


def sample_sigma(noise: Noise, data, level) -> np.ndarray:
    """σ of each row of *data*: the noise model at the row's level over √(raw samples averaged into the row)."""
    s = noise.at(level)
    count = getattr(data, "count", None)
    return s if count is None else s / np.sqrt(count) * np.where(count > 1, noise.mean_factor, 1.0)


def noise_estimate(data, values: np.ndarray, time_constant_s: float, relative: bool = False) -> Noise | None:
    """Noise of one channel of *data* (any sampling, ≥ 3 samples per test); None if no window exists.  A channel
    with one value in every row carries no measurement (a UserError naming it)."""
    if len(values) and float(np.ptp(values)) == 0.0:
        name = "torque_Nm" if values is data.torque_Nm else "drum_temp_C" if values is data.drum_temp_C else "a column"
        raise UserError(f"{data.source}, column '{name}': {float(values[0]):g} in every row — nothing was measured; "
                        f"check that the column holds the bench's {'torque' if name == 'torque_Nm' else 'readings'} "
                        f"(or the column map of the log)")
    raw = raw_rate_noise(data, values)
    if raw is not None:
        return raw
    fits = []
    order = np.lexsort((data.time_s, data.test_index))
    for p in range(1, MAX_DEGREE + 1):
        e, level, w, c = pseudo_residuals(data.time_s, values, data.test_index, time_constant_s, p, order,
                                          MAX_WINDOWS)
        if len(e) == 0:
            break
        a, b = _scale(e, level, relative)
        sig = np.sqrt(a * a + (b * level) ** 2)
        z_all = e / np.maximum(sig, 1e-300)
        tails = math.sqrt(float(np.mean(np.where(np.abs(z_all) < FAR, z_all ** 2, 0.0))))
        z = z_all[np.abs(z_all) < CLIP]
        kurt = float(np.mean(z ** 4) / max(np.mean(z ** 2), 1e-300) ** 2)
        dof = _effective_dof(w, c, kurt)
        fits.append((p, a, b, float(np.sqrt(np.mean(sig ** 2))), dof, tails))
    if not fits:
        return None
    k, note, reliable = 0, "", True
    while k + 1 < len(fits):
        (_, _, _, s0, d0, _), (_, _, _, s1, d1, _) = fits[k], fits[k + 1]
        if d1 < 3 or (s0 / s1) ** 2 <= special.fdtri(d0, d1, 1 - CURVATURE_P):
            break
        k += 1
    p, a, b, sigma, dof, tails = fits[k]
    if k + 1 == len(fits) and k > 0 and len(fits) > 1:
        (_, _, _, s_prev, d_prev, _) = fits[k - 1]
        if (s_prev / sigma) ** 2 > special.fdtri(d_prev, dof, 1 - CURVATURE_P) and p < MAX_DEGREE:
            reliable = False
            note = (f"the signal still curves between samples at the highest local degree the sampling allows "
                    f"({p}); σ = {sigma:.3g} is an upper bound")
    if dof < MIN_DOF:
        reliable = False
        note = note or (f"only {dof:.0f} effective degrees of freedom (too few samples per test); σ = {sigma:.3g} "
                        f"is uncertain")
    return Noise(sigma, dof, a, b, p, reliable, "data", note, mean_factor=max(tails, 1.0))
