"""Radiation beside convection in the drum's cooling law."""
from __future__ import annotations

import functools

import numpy as np

from rollaway.effects.base import Effect, EffectParameter

STEFAN_BOLTZMANN_W_m2K4 = 5.670374419e-8
KELVIN = 273.15


TABLE_SPAN_K = 1500.0         # a table of G reaches this far from the ambient (every start T_0 a fit allows);
                              # 2000 points: within 1 mK of a 40 000-point table, cooling from 300 °C, ε = 0.9
CACHE_SIZE = 8    # a fit asks for the same cooling again and again: every Jacobian column of a torque parameter


def radiative_convective_temperature_C(time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K,
                                       emissivity, cooled_area_m2, heat_capacity_J_K, n_grid=2000):
    """Lumped drum cooling by convection and radiation [°C] (:func:`_cooling_C`), the last :data:`CACHE_SIZE`
    answers kept: a fit's Jacobian columns of the torque's own parameters leave the cooling unchanged (half the calls
    of a diagnosis of a radiating drum repeat one of the last few).  The answer is read-only."""
    args = [np.asarray(x, float) for x in (time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K, emissivity)]
    key = (tuple(a.shape for a in args), b"".join(a.tobytes() for a in args), float(cooled_area_m2),
           float(heat_capacity_J_K), int(n_grid))
    out = _CACHE.pop(key, None)
    if out is None:
        out = _cooling_C(*args, cooled_area_m2, heat_capacity_J_K, n_grid)
        out.flags.writeable = False
        if len(_CACHE) >= CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))
    _CACHE[key] = out                     # the most recent last
    return out


_CACHE: dict[tuple, np.ndarray] = {}


AMBIENT_TABLES = 16          # more distinct ambients than this (a logged ambient): tables on a grid of them
AMBIENT_STEP_K = 2.0         # ... spaced this far, each sample interpolated between the two around its ambient


def _cooling_C(time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K, emissivity, cooled_area_m2,
               heat_capacity_J_K, n_grid):
    """:func:`_tabled_C`, with one table per distinct ambient — or, for more than :data:`AMBIENT_TABLES` of them
    (a logged ambient, one reading per sample), linear in the ambient between tables :data:`AMBIENT_STEP_K` apart
    (exact in the convective limit, where T is linear in T_amb; a drum cooling from 300 °C with ε = 0.9 is within
    0.4 mK of its table per ambient with tables 2 K apart, 5 mK with 8 K), each table built once for the samples
    below and above it."""
    t, t0, amb, h, eps = np.broadcast_arrays(*(np.asarray(x, float) for x in (
        time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K, emissivity)))
    distinct = np.unique(amb).size if amb.size > AMBIENT_TABLES else amb.size
    grid = (float(amb.max()) - float(amb.min())) / AMBIENT_STEP_K + 2.0 if amb.size else 0.0
    if distinct <= AMBIENT_TABLES or distinct <= 2.0 * grid:     # the grid would build more tables (wide draws)
        return _tabled_C(t, t0, amb, h, eps, cooled_area_m2, heat_capacity_J_K, n_grid)
    lo = np.floor(amb / AMBIENT_STEP_K) * AMBIENT_STEP_K
    w = (amb - lo) / AMBIENT_STEP_K
    both = _tabled_C(*(np.concatenate([x, x]) for x in (t, t0)), np.concatenate([lo, lo + AMBIENT_STEP_K]),
                     *(np.concatenate([x, x]) for x in (h, eps)), cooled_area_m2, heat_capacity_J_K, n_grid)
    below, above = both[:t.shape[0]], both[t.shape[0]:]
    return (1.0 - w) * below + w * above


def _tabled_C(time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K, emissivity, cooled_area_m2,
              heat_capacity_J_K, n_grid):
    """Lumped drum cooling by convection and radiation [°C].

    ``C dT/dt = −h A (T − T_a) − ε σ A (T_K⁴ − T_aK⁴)`` is separable: with s = ln(T − T_a),
    ``t(s) = G(s_0) − G(s)``, ``G(s) = ∫ (T − T_a)·C / q(T) ds``.  G is tabulated once per
    ambient on a log grid (smooth integrand, no stiffness) and inverted by interpolation,
    so all samples of all tests are done at once.  A drum that starts below the ambient warms
    towards it by the same law (s = ln(T_a − T), its own table).  The table spans :data:`TABLE_SPAN_K` whatever
    the samples' own start temperatures, so each sample's answer is its own (the same alone as among others:
    fits evaluate several value sets at once on stacked copies of the data).
    """
    t, t0, amb, h, eps = np.broadcast_arrays(*(np.asarray(x, float) for x in (
        time_s, initial_temp_C, ambient_C, heat_transfer_W_m2K, emissivity)))
    shape = t.shape
    t, t0 = t.ravel(), t0.ravel()
    out = np.empty(t.size)
    side = np.where(t0 >= amb.ravel(), 1.0, -1.0)          # +1 cooling towards the ambient, −1 warming
    keys = np.stack([amb.ravel(), h.ravel(), eps.ravel(), side], axis=1)
    for (ta, hj, ej, sg), sel in _key_groups(keys):       # one table of G per (ambient, h, ε, side)
        span = TABLE_SPAN_K if sg > 0 else min(TABLE_SPAN_K, 0.99 * (ta + KELVIN))   # no colder than 0 K
        top = max(span, float(np.max(sg * (t0[sel] - ta))) * 1.01)
        s, g, f0 = _table(float(ta), float(hj), float(ej), float(sg), top, float(cooled_area_m2),
                          float(heat_capacity_J_K), int(n_grid))
        d0 = np.clip(sg * (t0[sel] - ta), 1e-4, None)
        g_target = np.interp(np.log(d0), s, g) - t[sel]
        # below the grid the integrand is the pure-convection limit (f0): extend exponentially
        inside = g_target >= 0.0
        s_out = np.where(inside, np.interp(np.maximum(g_target, 0.0), g, s), s[0] + g_target / f0)
        out[sel] = ta + np.sign(t0[sel] - ta) * np.exp(s_out)      # a drum at the ambient stays there
    return out.reshape(shape)


TABLES = 64                  # the tables of G kept: a fit's Jacobian columns of the torque's parameters, and of a
                             # global the cooling does not read, ask for the same (ambient, h, ε, side) again


@functools.lru_cache(maxsize=TABLES)
def _table(ambient_C: float, h: float, eps: float, side: float, top_K: float, cooled_area_m2: float,
           heat_capacity_J_K: float, n_grid: int) -> tuple[np.ndarray, np.ndarray, float]:
    """The table of :func:`_tabled_C` for one (ambient, h, ε, side): the log grid s = ln|T − T_a| up to *top_K*,
    G(s) on it and the integrand at its lowest point (read-only arrays)."""
    s = np.linspace(np.log(1e-4), np.log(top_K), n_grid)
    d = np.exp(s)
    q = h * cooled_area_m2 * d + eps * STEFAN_BOLTZMANN_W_m2K4 * cooled_area_m2 * side * (
        (ambient_C + side * d + KELVIN) ** 4 - (ambient_C + KELVIN) ** 4)
    f = heat_capacity_J_K * d / q
    g = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(s))])   # increasing in s
    s.flags.writeable = g.flags.writeable = False
    return s, g, float(f[0])


MAX_RUNS = 256               # more runs of equal keys than this: group by sorting each column instead


def _key_groups(keys: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """(key row, indices of the samples with that key) for each distinct row of *keys*.  Keys come in runs (a
    parameter set's copy of the data, a test warming instead of cooling): runs are found by comparing neighbours
    and runs with equal keys joined, without the row sort of ``np.unique(axis=0)`` (40× the table's own cost on
    stacked copies); many runs fall back to sorting each column and then one integer code per row (the same
    groups, in the order of ``np.unique(axis=0)``)."""
    n = len(keys)
    if n == 0:
        return []
    change = np.flatnonzero(np.any(keys[1:] != keys[:-1], axis=1)) + 1
    if change.size == 0:                                     # one key for all samples
        return [(keys[0], np.arange(n))]
    if change.size > MAX_RUNS:            # each column's codes, combined into one integer per row
        code = np.zeros(n, np.int64)
        for col in keys.T:
            _, inv = np.unique(col, return_inverse=True)
            code = code * (int(inv.max()) + 1) + inv.ravel()
        first, inverse = np.unique(code, return_index=True, return_inverse=True)[1:]
        inverse = inverse.ravel()
        order = np.argsort(inverse, kind="stable")
        bounds = np.concatenate([[0], np.cumsum(np.bincount(inverse, minlength=len(first)))])
        return [(keys[f], order[bounds[j]:bounds[j + 1]]) for j, f in enumerate(first)]
    starts, ends = np.concatenate([[0], change]), np.concatenate([change, [n]])
    groups: dict[tuple, list[np.ndarray]] = {}
    for a, b in zip(starts, ends):
        groups.setdefault(tuple(keys[a]), []).append(np.arange(a, b))
    return [(np.array(k), np.concatenate(v)) for k, v in groups.items()]


class RadiationCooling(Effect):
    name = "radiation_cooling"
    elementwise = True                # each sample's temperature from its own inputs (fixed table span)
    summary = "the drum also loses heat by radiation, not only by convection"
    physics = ("ρ c_p V dT/dt = −h A (T − T_amb) − ε σ A (T⁴ − T_amb⁴) (absolute temperatures), replacing the "
               "paper's pure-convection eq. (10); σ = 5.67e-8 W m⁻² K⁻⁴, A = A_conv.")
    signature = ("drum-temperature residual: the hot start cools faster and the cool tail more slowly than any "
                 "single exponential (a curved residual against temperature after h is refitted); the torque "
                 "follows through ΔT")
    reference = ("Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, 6th ed. 2007, §1.2.3 and §12.3; "
                 "Limpert 1999 §3 (brake cooling by convection and radiation)")
    parameters = (EffectParameter("emissivity", "–", neutral=0.0, lower=0.0, upper=1.0, initial=0.2,
                                  typical=0.8, description="total hemispherical emissivity of the drum"),)

    def drum_temperature(self, state, temp_C, v):
        p = state.params
        return radiative_convective_temperature_C(
            state.time_s, state.initial_temp_C, state.ambient_C, state.heat_transfer_W_m2K, v["emissivity"],
            p.cooled_area_m2, p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3)
