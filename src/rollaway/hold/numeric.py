"""Numeric hold check for a drum model with effects: least margin, slip time, least hand force.

The paper's chain has closed forms (:mod:`rollaway.hold.closed_form`); an effect can make the torque
non-monotone in time (a lagging lining, a relaxing clamp force) or non-affine in the hand
force, so here each point is solved numerically, vectorised over points:

* **least margin** over [0, D]: dense evaluation on :data:`GRID_POINTS` instants, then the
  grid minimum is refined by a bracketing minimiser (``scipy.optimize.elementwise.find_minimum``);
* **slip time**: the first grid interval in which the margin falls below 1, refined by a
  bracketing root finder (``scipy.optimize.elementwise.find_root``, Chandrupatla);
* **least hand force**: the root of ``least_margin(F) − 1`` in F (the clamp force grows with
  the hand force through u_6, eq. 24), bracketed by doubling from :data:`FORCE_START_N`.

The margin is ``2·T_gen(t)/T_req`` (eqs. 17b and 23; two rear drums).  Functions take
per-point arrays of equal shape (P,) and return (P,) arrays.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import elementwise

from rollaway.model.drum_model import DrumModel

GRID_POINTS = 801            # instants of the dense evaluation over [0, D] [assumed: ≥ 4 per effect time constant]
CHUNK_POINTS = 512           # points evaluated together (memory: CHUNK × GRID floats per array)
FORCE_START_N = 500.0        # first upper bracket of the least hand force [N]
FORCE_MAX_N = 1e5            # no hand force above this is sought: "no force can hold" [N]
_TOL = dict(xrtol=1e-12, xatol=1e-9)


class MarginFunction:
    """Brake margin 2·T_gen/T_req of P points as an elementwise function of (time, point index)."""

    def __init__(self, model: DrumModel, hand_force_N, sign, t_req_Nm, mu_drum, gap_m, initial_temp_C,
                 heat_transfer_W_m2K=None, values: dict | None = None):
        p = model.params
        self.model = model
        values = dict(values or {})
        if gap_m is None and "gap_m" in values:        # a held gap drawn with the other brake parameters
            gap_m = values.pop("gap_m")
        shape = np.broadcast_shapes(*(np.shape(x) for x in (hand_force_N, sign, t_req_Nm, mu_drum, gap_m,
                                                             initial_temp_C)))
        arr = lambda x, default: np.broadcast_to(np.asarray(default if x is None else x, float), shape).ravel()  # noqa
        self.force = arr(hand_force_N, 0.0)
        self.sign = arr(sign, 1.0)
        self.t_req = arr(t_req_Nm, 1.0)
        self.mu = arr(mu_drum, p.mu_drum)
        self.gap = arr(gap_m, p.gap_m)
        self.t0 = arr(initial_temp_C, p.initial_drum_temp_C)
        self.h = arr(heat_transfer_W_m2K, p.heat_transfer_W_m2K)
        self.values = {k: arr(v, 0.0) for k, v in values.items()}   # per-point effect values (draws)
        self.shape = shape

    def __len__(self) -> int:
        return self.force.size

    def __call__(self, time_s, index, force_N=None):
        """Margin at *time_s* for points *index* (broadcast), optionally at another hand force."""
        i = np.asarray(index, int)
        f = self.force[i] if force_N is None else force_N
        s = self.model.evaluate(time_s, f, self.sign[i], mu_drum=self.mu[i], gap_m=self.gap[i],
                                initial_temp_C=self.t0[i], heat_transfer_W_m2K=self.h[i],
                                values={k: v[i] for k, v in self.values.items()} or None)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.t_req[i] > 0, 2.0 * s.torque_Nm / np.where(self.t_req[i] > 0, self.t_req[i], 1.0),
                            np.inf)


def _grid(duration_s, n=GRID_POINTS):
    return np.asarray(duration_s, float)[..., None] * np.linspace(0.0, 1.0, n)


def least_margin(fn: MarginFunction, duration_s, force_N=None, return_time: bool = False):
    """Least margin over [0, duration_s] per point (and the instant, with *return_time*)."""
    n = len(fn)
    dur = np.broadcast_to(np.asarray(duration_s, float), (n,))
    force = None if force_N is None else np.broadcast_to(np.asarray(force_N, float), (n,))
    m_out, t_out = np.empty(n), np.empty(n)
    for lo in range(0, n, CHUNK_POINTS):
        idx = np.arange(lo, min(lo + CHUNK_POINTS, n))
        t = _grid(dur[idx])
        f_arg = None if force is None else force[idx][:, None]
        m = fn(t, idx[:, None], f_arg)
        k = np.argmin(m, axis=1)
        rows = np.arange(len(idx))
        m_min, t_min = m[rows, k], t[rows, k]
        inner = (k > 0) & (k < t.shape[1] - 1) & np.isfinite(m_min)
        if np.any(inner):
            r = rows[inner]
            f_in = None if force is None else force[idx][r]

            def fun(x, j, fj=None):
                return fn(x, j, fj)
            args = (idx[r],) if f_in is None else (idx[r], f_in)
            res = elementwise.find_minimum(fun, (t[r, k[r] - 1], t[r, k[r]], t[r, k[r] + 1]), args=args,
                                           tolerances=dict(xrtol=1e-10, xatol=1e-9))
            better = np.isfinite(res.f_x) & (res.f_x < m_min[r])
            m_min[r] = np.where(better, res.f_x, m_min[r])
            t_min[r] = np.where(better, res.x, t_min[r])
        m_out[idx], t_out[idx] = m_min, t_min
    return (m_out, t_out) if return_time else m_out


def first_slip_time(fn: MarginFunction, duration_s) -> np.ndarray:
    """First instant in [0, duration_s] at which the margin is below 1 (NaN if it never is) [s]."""
    n = len(fn)
    dur = np.broadcast_to(np.asarray(duration_s, float), (n,))
    out = np.full(n, np.nan)
    for lo in range(0, n, CHUNK_POINTS):
        idx = np.arange(lo, min(lo + CHUNK_POINTS, n))
        t = _grid(dur[idx])
        m = fn(t, idx[:, None])
        below = m < 1.0
        first = np.where(below.any(axis=1), np.argmax(below, axis=1), -1)
        rows = np.arange(len(idx))
        res_t = np.full(len(idx), np.nan)
        res_t[first == 0] = 0.0
        # a dip below 1 between grid instants: the refined least margin finds it
        none = first < 0
        if np.any(none):
            d = dur[idx][none]
            m_min, t_min = least_margin(Subset(fn, idx[none]), d, return_time=True)
            dip = m_min < 1.0
            r = rows[none][dip]
            step = d[dip] / (t.shape[1] - 1)
            res_t[r] = _root_in(fn, idx[r], np.floor(t_min[dip] / step) * step, t_min[dip])
        mid = first > 0
        if np.any(mid):
            r = rows[mid]
            res_t[r] = _root_in(fn, idx[r], t[r, first[r] - 1], t[r, first[r]])
        out[idx] = res_t
    return out


def _root_in(fn, index, t_lo, t_hi):
    """Instant in (t_lo, t_hi] at which the margin crosses 1 (margin ≥ 1 at t_lo, < 1 at t_hi)."""
    res = elementwise.find_root(lambda x, j: fn(x, j) - 1.0, (t_lo, t_hi), args=(index,), tolerances=_TOL)
    return np.where(np.isfinite(res.x), res.x, t_hi)


class Subset:
    """The same margin function restricted to some points (indices renumbered from 0)."""

    def __init__(self, fn: MarginFunction, index):
        self.fn, self.index = fn, np.asarray(index, int)

    def __len__(self):
        return self.index.size

    def __call__(self, time_s, index, force_N=None):
        return self.fn(time_s, self.index[np.asarray(index, int)], force_N)


def least_hand_force(fn: MarginFunction, duration_s) -> np.ndarray:
    """Least hand force whose least margin over [0, duration_s] is ≥ 1 [N]; inf if none up to FORCE_MAX_N."""
    n = len(fn)
    dur = np.broadcast_to(np.asarray(duration_s, float), (n,))
    out = np.full(n, np.inf)
    flat = fn.t_req <= 0
    out[flat] = 0.0
    todo = np.flatnonzero(~flat)
    if todo.size == 0:
        return out
    sub = Subset(fn, todo)
    m_zero = least_margin(sub, dur[todo], force_N=0.0)
    out[todo[m_zero >= 1.0]] = 0.0
    todo = todo[m_zero < 1.0]
    hi = np.full(todo.size, FORCE_START_N)
    while todo.size:
        m_hi = least_margin(Subset(fn, todo), dur[todo], force_N=hi)
        ok = m_hi >= 1.0
        if np.any(ok):
            r = np.flatnonzero(ok)
            sub = Subset(fn, todo[r])
            res = elementwise.find_root(lambda f, j, d: least_margin_at(sub, j, d, f) - 1.0,
                                        (hi[r] / 2.0 * (hi[r] > FORCE_START_N), hi[r]),
                                        args=(np.arange(r.size), dur[todo[r]]), tolerances=dict(xrtol=1e-10, xatol=1e-7))
            out[todo[r]] = np.where(np.isfinite(res.x), res.x, hi[r])
        todo, hi = todo[~ok], hi[~ok] * 2.0
        keep = hi <= FORCE_MAX_N
        todo, hi = todo[keep], hi[keep]
    return out


def least_margin_at(fn, index, duration_s, force_N):
    """Least margin of points *index* of *fn* at hand forces *force_N* (elementwise in all three)."""
    index, duration_s, force_N = np.broadcast_arrays(np.asarray(index, int), np.asarray(duration_s, float),
                                                     np.asarray(force_N, float))
    shape = index.shape
    sub = Subset(fn, index.ravel())
    return least_margin(sub, duration_s.ravel(), force_N=force_N.ravel()).reshape(shape)
