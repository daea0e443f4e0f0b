"""Lumped convective cooling of the drum (paper eqs. 1/9 and 2/10).

Ishak et al. (2018) assume convection dominates (after Wolff 2010), giving Newton's
law of cooling for a lumped drum of mass ρV and heat capacity c_p.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def cooling_time_constant_s(density_kg_m3: ArrayLike, specific_heat_J_kgK: ArrayLike,
                            volume_m3: ArrayLike, heat_transfer_W_m2K: ArrayLike,
                            cooled_area_m2: ArrayLike) -> np.ndarray:
    """Time constant τ = ρ c_p V / (h A) of the lumped drum [s] (exponent of eq. 10)."""
    return (np.asarray(density_kg_m3, float) * specific_heat_J_kgK * volume_m3
            / (np.asarray(heat_transfer_W_m2K, float) * cooled_area_m2))


def drum_temperature_C(time_s: ArrayLike, initial_temp_C: ArrayLike, ambient_temp_C: ArrayLike,
                       time_constant_s: ArrayLike) -> np.ndarray:
    """Drum temperature after *time_s* of cooling, eq. (2)/(10) [°C].

    ``T(t) = (T_0 − T_amb)·exp(−t/τ) + T_amb``, t counted from the lever's application.
    """
    t = np.asarray(time_s, float)
    return (np.asarray(initial_temp_C, float) - ambient_temp_C) * np.exp(-t / time_constant_s) + ambient_temp_C


def temperature_change_K(drum_temp_C: ArrayLike, initial_temp_C: ArrayLike) -> np.ndarray:
    """ΔT = T(t) − T_0, eq. (1)/(9) [K]; negative while the drum cools."""
    return np.asarray(drum_temp_C, float) - initial_temp_C


def drum_temperature_logged_ambient_C(time_s: ArrayLike, initial_temp_C: ArrayLike, ambient_C: ArrayLike,
                                      time_constant_s: ArrayLike, test_index: ArrayLike) -> np.ndarray:
    """Drum temperature cooling towards a logged, time-varying ambient [°C].

    Integrates eq. (9)/(10)'s ODE ``dT/dt = −(T − T_amb(t))/τ`` exactly for an ambient that is
    linear between consecutive samples of a test (the logged series, one reading per sample).
    Over a step Δ with ambient a_j → a_{j+1} (slope m = (a_{j+1} − a_j)/Δ):
    ``T_{j+1} = a_{j+1} − m·τ + (T_j − a_j + m·τ)·e^{−Δ/τ}``; a constant ambient gives eq. (10).

    Rows of each test (``test_index``) must be in time order and start at its first sample,
    where ``T = initial_temp_C``.  Vectorised across tests: one step per sample position.
    """
    t = np.asarray(time_s, float)
    amb = np.broadcast_to(np.asarray(ambient_C, float), t.shape)
    t0 = np.broadcast_to(np.asarray(initial_temp_C, float), t.shape)
    tau = np.broadcast_to(np.asarray(time_constant_s, float), t.shape)
    out = np.empty_like(t)
    if not t.size:
        return out
    order, first, cell, back = _layout(np.asarray(test_index))
    out[order] = _tests(t[cell], t0[first], amb[cell], tau[cell])[back]
    return out


_LAYOUTS: dict = {}           # test_index bytes → its tests × samples layout (a fit evaluates the same rows often)


def _layout(idx: np.ndarray) -> tuple:
    """Rows grouped by test in time order (*order*), each test's first row, the tests × samples table of row
    numbers (a shorter test padded with its last row: inert steps) and where each of *order*'s rows sits in it."""
    key = (idx.dtype.str, idx.tobytes())
    got = _LAYOUTS.get(key)
    if got is None:
        order = np.argsort(idx, kind="stable")
        starts = np.flatnonzero(np.r_[True, idx[order][1:] != idx[order][:-1]])
        lengths = np.diff(np.r_[starts, len(order)])
        group = np.repeat(np.arange(len(starts)), lengths)
        pos = np.arange(len(order)) - np.repeat(starts, lengths)
        last = (starts + lengths - 1)[:, None]
        cell = order[np.minimum(starts[:, None] + np.arange(lengths.max())[None, :], last)]
        got = (order, order[starts], cell, (group, pos))
        if len(_LAYOUTS) > 64:
            _LAYOUTS.clear()
        _LAYOUTS[key] = got
    return got


def _one_test(t: np.ndarray, t0: float, amb: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """The recursion of :func:`drum_temperature_logged_ambient_C` over one test's samples (:func:`_tests`)."""
    return _tests(t[None, :], np.atleast_1d(t0), amb[None, :], tau[None, :])[0]


def _tests(t: np.ndarray, t0: np.ndarray, amb: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """The recursion of :func:`drum_temperature_logged_ambient_C` over tests × samples (one row per test, padded
    rows repeat their last sample), T_{j+1} = E_j·T_j + c_j with E_j = e^{−Δ_j/τ}: in closed form
    T_k = e^{−S_k}·(T_0 + Σ_{j<k} c_j·e^{S_{j+1}}), S the running sum of Δ/τ (cumulative sums along each row, no
    loop over samples); stepped one sample at a time in a row where e^{S} would overflow."""
    dt = np.diff(t, axis=1)
    step = dt / tau[:, 1:]
    slope = np.diff(amb, axis=1) / np.where(dt > 0, dt, 1.0)
    m_tau = slope * tau[:, 1:]
    decay = np.exp(-step)
    c = amb[:, 1:] - m_tau - (amb[:, :-1] - m_tau) * decay
    s = np.cumsum(step, axis=1)
    out = np.empty_like(t)
    out[:, 0] = t0
    if s.shape[1]:
        big = s[:, -1] > 600.0                       # e^{S} beyond ~1e260: one sample after another
        with np.errstate(over="ignore", invalid="ignore"):
            out[:, 1:] = np.exp(-s) * (t0[:, None] + np.cumsum(c * np.exp(s), axis=1))
        for r in np.flatnonzero(big):
            for j in range(dt.shape[1]):
                out[r, j + 1] = decay[r, j] * out[r, j] + c[r, j]
    return out
