"""The limit state of a population: least brake margin and tyre margin of N sampled cars at once.

A car rolls away when, within ``duration_s``, its brake slips (least hold margin ``2·T_gen/T_req`` < 1,
eqs. 17b and 23) or its rear tyres skid (adhesion margin ``μ_r·N_r/(m g sin θ)`` < 1, eq. 22 with the
slope balance); with ``direction = "both"`` it must hold facing either way (the least margin of the two).

* **paper's chain** (no effect active): the closed forms of :mod:`rollaway.hold.closed_form`, evaluated
  once for all N cars — every parameter may be an (N,) array (a parameter set whose fields are arrays;
  the chain is plain numpy), so any parameter can vary;
* **model with effects**: the torque may dip inside the hold, so the margin is evaluated on a time grid
  of :data:`SCREEN_POINTS` instants per car, and the cars whose screened minimum is below
  :data:`REFINE_BELOW` again by the numeric hold check (:func:`rollaway.hold.numeric.least_margin`: its
  grid and bracketing refinement), or — where a car varies a drum parameter that check does not take
  per point — on its :data:`rollaway.hold.numeric.GRID_POINTS`-instant grid.

A calibrated model brings its own uncertainty (:mod:`rollaway.uncertainty.draws`,
:mod:`rollaway.uncertainty.predictive`): each car also gets one competing effect set (by its weight),
one draw of the fitted values (as a deviation from the fitted value, added to the car's own value
where the population varies the same name) and one model error ε (torque × (1 + ε): the margin scales), and
where the record has one, the error of the start of the hold (:func:`rollaway.uncertainty.predictive.
start_error_draws`; such cars are evaluated on the time grid).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from rollaway.hold.closed_form import min_brake_margin, required_torque, tyre_adhesion_margin
from rollaway.hold.numeric import GRID_POINTS
from rollaway.model.drum_model import DrumModel
from rollaway.model.parameters import SPEC_BY_NAME

SCREEN_POINTS = 41        # instants of the first pass over a hold with effects [assumed: ≥ 4 per effect time constant of minutes]
REFINE_BELOW = 1.25       # screened margins below this are evaluated again on the fine grid [assumed]
CHUNK_CARS = 4096         # cars evaluated together on a time grid (memory: CHUNK × grid floats per array)
# parameters the numeric hold check takes per point, and those that act only through T_req and the tyres:
# cars near the boundary that vary only these are refined by rollaway.hold.numeric.least_margin itself
POINT_ARGS = frozenset({"mu_drum", "gap_m", "initial_drum_temp_C", "heat_transfer_W_m2K"})
VEHICLE_ONLY = frozenset({"vehicle_mass_kg", "occupant_mass_kg", "wheel_radius_m", "gravity_m_s2", "wheelbase_m",
                          "track_m", "cg_behind_front_m", "cg_height_m", "tyre_road_mu", "front_seat_behind_front_m",
                          "rear_seat_behind_front_m", "seat_height_m"})


@dataclass(frozen=True)
class Margins:
    """Per car: least brake margin over the hold and tyre margin (least over the directions)."""

    brake: np.ndarray
    tyre: np.ndarray

    @property
    def least(self) -> np.ndarray:
        return np.minimum(self.brake, self.tyre)

    @property
    def fails(self) -> np.ndarray:
        return self.least < 1.0


def _split(values: dict[str, np.ndarray], base_params):
    """Scenario numbers and a parameter set whose varied fields are arrays."""
    params = {k: np.asarray(v, float) for k, v in values.items() if k in SPEC_BY_NAME}
    scen = {k: np.asarray(v, float) for k, v in values.items() if k not in SPEC_BY_NAME}
    return scen, dataclasses.replace(base_params, **params) if params else base_params


def margins(population, values: dict[str, np.ndarray], n: int | None = None, draws: dict | None = None) -> Margins:
    """Margins of the cars with these varied *values* ({name: (N,) array}) and model *draws* (see :func:`model_draws`)."""
    n = n if n is not None else len(next(iter(values.values())))
    base = population.base
    groups = draws["groups"] if draws else [(np.arange(n), population.model, {})]
    brake, tyre = np.empty(n), np.empty(n)
    start = (draws or {}).get("start")
    for k, (idx, model, fitted) in enumerate(groups):
        if idx.size == 0:
            continue
        own_start = None if start is None or start[1][k] is None else (start[0][idx], start[1][k])
        sub = {k: np.broadcast_to(v, (n,))[idx] for k, v in values.items()}
        for k, dv in fitted.items():          # fitted-value draws: deviations from the fitted value
            if k in SPEC_BY_NAME:
                sub[k] = sub.get(k, getattr(model.params, k)) + dv[idx]
        scen, params = _split(sub, model.params)
        effect_values = {k: v[idx] for k, v in (draws or {}).get("effects", {}).items() if k in model.values}
        f = scen.get("hand_force_N", base.hand_force_N)
        g = scen.get("grade_pct", base.grade_pct)
        occ = scen.get("occupants", float(base.occupants))
        dur = scen.get("duration_s", base.duration_s)
        b, t = np.full(idx.size, np.inf), np.full(idx.size, np.inf)
        for d in population.directions:
            t = np.minimum(t, tyre_adhesion_margin(params, g, d, occ))
            if model.has_effects or effect_values or own_start is not None:
                m = _least_margin_with_effects(model, params, effect_values, f, g, d, occ, dur, idx.size, own_start)
            else:
                m = min_brake_margin(params, f, g, d, occ, dur)
            if draws is not None and "friction_z" in draws:     # a direction the bench did not test
                m = _carried(population.model, params, g, d, m, draws["friction_z"][idx])
            b = np.minimum(b, np.broadcast_to(m, (idx.size,)))
        if draws is not None and "eps" in draws:
            b = b * (1.0 + draws["eps"][idx])
        brake[idx], tyre[idx] = b, np.broadcast_to(t, (idx.size,))
    return Margins(brake, tyre)


def _carried(model: DrumModel, params, grade, direction: str, margin, z) -> np.ndarray:
    """*margin* of cars facing *direction* on *grade*, carried over where their effective direction is one
    *model*'s bench did not test (:func:`rollaway.uncertainty.direction.untested_direction_factor`: a friction
    coefficient drawn apart from each car's μ_d, its place in the posterior *z*)."""
    from rollaway.hold.closed_form import _effective
    from rollaway.uncertainty.direction import carried_over, carry_factor
    _, sign = _effective(grade, direction)
    sign = np.broadcast_to(np.asarray(sign, float), np.shape(z))
    carry = carried_over(model, sign)
    if not np.any(carry):
        return margin
    f = carry_factor(params.mu_drum, params.shoe_arm_normal_m, params.shoe_arm_friction_m, sign, z)
    return margin * np.where(carry, f, 1.0)


def _least_margin_with_effects(model: DrumModel, params, effect_values, force, grade, direction, occupants,
                               duration_s, n: int, start=None) -> np.ndarray:
    """Least brake margin of n cars of a model with effects: a screening grid, then the fine grid near 1.
    *start*: (each car's start error, the record's ``model_error_start``) on the torque at the start of the hold
    (:class:`rollaway.uncertainty.predictive.StartError`)."""
    from rollaway.uncertainty.predictive import StartError, start_weight
    from rollaway.hold.closed_form import _effective
    g, sign = _effective(grade, direction)
    t_req = np.broadcast_to(required_torque(params, g, occupants), (n,))
    per_car = {k: np.broadcast_to(getattr(params, k), (n,)) for k in SPEC_BY_NAME
               if np.ndim(getattr(params, k)) > 0}
    cars = dict(force=np.broadcast_to(np.asarray(force, float), (n,)), sign=np.broadcast_to(sign, (n,)),
                t_req=t_req, dur=np.broadcast_to(np.asarray(duration_s, float), (n,)))
    vals = {k: np.broadcast_to(v, (n,)) for k, v in effect_values.items()}

    def grid_min(idx, points):
        out = np.empty(idx.size)
        for lo in range(0, idx.size, max(CHUNK_CARS * 41 // points, 16)):
            j = idx[lo:lo + max(CHUNK_CARS * 41 // points, 16)]
            col = lambda a: np.asarray(a)[j][:, None]  # noqa: E731
            p = dataclasses.replace(model.params, **{k: col(v) for k, v in per_car.items()}) if per_car \
                else model.params
            m = model.with_params(p)
            t = col(cars["dur"]) * np.linspace(0.0, 1.0, points)[None, :]
            s = m.evaluate(t, col(cars["force"]), col(cars["sign"]),
                           values={k: col(v) for k, v in vals.items()} or None)
            with np.errstate(divide="ignore", invalid="ignore"):
                marg = np.where(col(cars["t_req"]) > 0, 2.0 * s.torque_Nm / col(cars["t_req"]), np.inf)
            if start is not None:
                marg = marg * (1.0 + col(start[0]) * start_weight(t, start[1]))
            out[lo:lo + j.size] = np.min(marg, axis=1)
        return out

    everyone = np.arange(n)
    least = grid_min(everyone, SCREEN_POINTS)
    near = np.flatnonzero(least < REFINE_BELOW)
    if near.size and set(per_car) <= POINT_ARGS | VEHICLE_ONLY:    # the numeric hold check itself
        from rollaway.hold.numeric import MarginFunction, least_margin
        per = lambda k: None if k not in per_car else per_car[k][near]  # noqa: E731
        fn = MarginFunction(model, cars["force"][near], cars["sign"][near], cars["t_req"][near], per("mu_drum"),
                            per("gap_m"), per("initial_drum_temp_C"), per("heat_transfer_W_m2K"),
                            values={k: v[near] for k, v in vals.items()} or None)
        if start is not None:
            fn = StartError(fn, np.asarray(start[0])[near], start[1])
        least[near] = least_margin(fn, cars["dur"][near])
    elif near.size:
        least[near] = np.minimum(least[near], grid_min(near, GRID_POINTS))
    return least


def model_draws(population, n: int, rng: np.random.Generator) -> dict | None:
    """A calibrated model's own scatter for n cars: competing effect set, fitted values, model error.

    None for a model without covariance, model error or competing effect sets.  The model error is
    widened for questions beyond the tested range at the population's median values
    (:func:`rollaway.uncertainty.predictive.extrapolation`).
    """
    from rollaway.uncertainty.direction import mixture_parts, untested_direction
    from rollaway.uncertainty.draws import draw_values, hold_error, own_record, torque_level_ratio, zero_torque_force
    from rollaway.physics.drum import direction_sign
    from rollaway.uncertainty.predictive import (edge_sd, extrapolation, measured_factor, model_error_draws,
                                                 start_error_draws)

    model = population.model
    pred = model.predictive
    if model.covariance is None and not pred and not model.alternatives:
        return None
    parts = mixture_parts(model, population.directions[0])
    owner = rng.choice(len(parts), size=n, p=np.array([w for w, _ in parts]) / sum(w for w, _ in parts))
    groups, effects = [], {}
    for k, (_, m) in enumerate(parts):
        idx = np.flatnonzero(owner == k)
        fitted = {}
        if m.covariance is not None and idx.size:
            d = _draw_chunked(m, idx.size, int(rng.integers(2**31)), draw_values,
                              untested_direction(model, population.directions[0]))
            centre = m.fitted_values()
            for name, v in d.items():
                if name == "shoe_arm_ratio":
                    fitted["shoe_arm_friction_m"] = (v - centre[name]) * m.params.shoe_arm_normal_m
                elif name in SPEC_BY_NAME:
                    fitted[name] = v - centre[name]
                else:
                    full = effects.setdefault(name, np.full(n, m.values.get(name, 0.0)))
                    full[idx] = v
        groups.append((idx, m, {k2: _scatter(v, idx, n) for k2, v in fitted.items()}))
    for k, (_, m) in enumerate(parts):     # effect values not drawn: the model's own
        for name, v in m.values.items():
            full = effects.setdefault(name, np.full(n, v))
            if m.covariance is None or name not in m.covariance.names:
                full[owner == k] = v
    pop = population
    force, t0, hold = pop.fixed("hand_force_N"), pop.fixed("initial_drum_temp_C"), pop.fixed("duration_s")
    level = torque_level_ratio(model, force, pred.get("tested_hand_force_N"),
                               float(direction_sign(pop.directions[0])), t0, hold)
    f0 = zero_torque_force(model)
    factor, _ = extrapolation(pred, hand_force_N=force, direction=pop.directions[0], initial_temp_C=t0,
                              duration_s=hold, zero_torque_force_N=f0, level_ratio=level)
    eps, extra, starts = np.empty(n), np.zeros(n), []
    for k, (_, m) in enumerate(parts):     # each effect set errs by its own held-out record (and force extrapolation)
        own = own_record(pred, m)
        mine = owner == k
        edge, measured = edge_sd(own, force, f0, level), measured_factor(own, factor, force, f0, level)
        hold_err = hold_error(m, force, float(direction_sign(pop.directions[0])), t0, hold)
        eps[mine] = model_error_draws(own, int(np.sum(mine)), factor, rng, edge, measured, hold_err)
        more = start_error_draws(own, int(np.sum(mine)), factor, rng, edge, measured, hold_err)
        starts.append(None if more is None else own["model_error_start"])
        if more is not None:
            extra[mine] = more
    out = {"groups": groups, "effects": effects, "eps": eps}
    if any(st is not None for st in starts):    # the start of the hold errs by the record's start error too
        out["start"] = (extra, starts)
    if len(pred.get("tested_directions") or ()) == 1:     # the untested direction's friction coefficient (_carried)
        out["friction_z"] = rng.standard_normal(n)
    return out


def _draw_chunked(model, n, seed, draw_values, marginal=False):
    step = 1_000_000
    parts = [draw_values(model, min(step, n - lo), seed + lo, marginal) for lo in range(0, n, step)]
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def _scatter(v, idx, n):
    out = np.zeros(n)
    out[idx] = v
    return out
