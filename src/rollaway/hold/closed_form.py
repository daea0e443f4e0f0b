"""Closed-form hold check: margins, slip time and least hand force of the paper's chain (docs/model.md).

Two conditions, both from a static balance:

* **brake**: hold margin ``2·T_gen(t) / T_req`` ≥ 1 (paper eqs. 17b and 23; the hand lever
  drives both rear drums through an equaliser, eq. 24 is per drum);
* **tyres**: adhesion margin ``μ_r·N_r / (m g sin θ)`` ≥ 1 (eq. 22 with the rear-axle load
  N_r from the slope balance in :func:`rollaway.physics.vehicle.rear_axle_load_N`).
  The paper checks only the first.

Grades are signed: a negative grade flips the direction the car faces relative to
the fall line (a car "facing downhill" on −20 % faces uphill on 20 %).
Everything is vectorised.  Every function takes a parameter set or a
:class:`~rollaway.model.drum_model.DrumModel`.  For the paper's chain closed forms replace scans (it is
affine in u_6 and ΔT, and ΔT(t) is monotone); a model with effects is solved numerically
(:mod:`rollaway.hold.numeric`: dense evaluation plus bracketing refinement).  The verdict of one
case is put together in :mod:`rollaway.hold.verdict`.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from rollaway.model.brake import drum_temperature, shoe_factor, unenergised_force
from rollaway.errors import UserError
from rollaway.model.drum_model import DrumModel, as_model
from rollaway.model.parameters import BrakeParameters
from rollaway.physics import drum as drum_phys
from rollaway.physics import vehicle

MAX_OCCUPANTS = 5
MAX_HAND_FORCE_N = 5000.0   # assumed: far above any hand (FMVSS 135 / UN R13-H use 400 N); same as the bench CSV


def _reject_bad(values: np.ndarray, bad: np.ndarray, message: str) -> np.ndarray:
    """Raise UserError with *message* formatted with the first bad value, else return *values*."""
    if np.any(bad):
        raise UserError(message.format(np.atleast_1d(values)[np.atleast_1d(bad)][0]))
    return values


def invalid_grade(grade_pct: ArrayLike) -> np.ndarray:
    """True where a grade is outside (−100 %, 100 %] or not finite."""
    g = np.asarray(grade_pct, float)
    return ~np.isfinite(g) | (g <= -100.0) | (g > 100.0)


def invalid_occupants(occupants: ArrayLike) -> np.ndarray:
    """True where the number of occupants is not a whole number from 0 to MAX_OCCUPANTS."""
    n = np.asarray(occupants, float)
    return ~np.isfinite(n) | (n < 0) | (n > MAX_OCCUPANTS) | (n != np.round(n))


def invalid_hand_force(hand_force_N: ArrayLike) -> np.ndarray:
    """True where a hand force is outside [0, MAX_HAND_FORCE_N] or not finite."""
    f = np.asarray(hand_force_N, float)
    return ~np.isfinite(f) | (f < 0) | (f > MAX_HAND_FORCE_N)


def validate_grade(grade_pct: ArrayLike) -> np.ndarray:
    return _reject_bad(np.asarray(grade_pct, float), invalid_grade(grade_pct),
                       "grade {:g} % is outside (−100 %, 100 %]; give the slope in percent rise over run, "
                       "e.g. 20 for a 20 % grade")


def validate_occupants(occupants: ArrayLike) -> np.ndarray:
    return _reject_bad(np.asarray(occupants, float), invalid_occupants(occupants),
                       "occupants = {:g} is not a whole number from 0 to %d; give the number of 70 kg occupants"
                       % MAX_OCCUPANTS)


def validate_hand_force(hand_force_N: ArrayLike) -> np.ndarray:
    return _reject_bad(np.asarray(hand_force_N, float), invalid_hand_force(hand_force_N),
                       "hand force {:g} N is negative, over %g N or not finite; give the lever force in newtons, "
                       "e.g. 400" % MAX_HAND_FORCE_N)


def _effective(grade_pct, direction):
    g = validate_grade(grade_pct)
    sign = drum_phys.direction_sign(direction) * np.where(g < 0, -1.0, 1.0)
    return np.abs(g), sign


def effective_slope(grade_pct: ArrayLike, direction="downhill"):
    """(|grade| [%], facing) with a negative grade folded into the facing (module docstring).

    Scalars in, scalars out (``(20.0, "uphill")``); arrays broadcast.
    """
    g, sign = _effective(grade_pct, direction)
    facing = _direction_of(sign)
    if np.ndim(facing) == 0:
        return float(g), str(facing)
    return g, facing


def _direction_of(sign):
    up_down = np.array(["uphill", "downhill"])          # a take is ~10x faster than np.where on strings
    return up_down[(np.asarray(sign) > 0).astype(np.intp)]


Model = BrakeParameters | DrumModel
NUMERIC_HORIZON_S = 7 * 86400.0   # the numeric slip time is sought up to this horizon when none is given


def _params(model_or_params) -> BrakeParameters:
    return model_or_params.params if isinstance(model_or_params, DrumModel) else model_or_params


def _numeric(model_or_params) -> DrumModel | None:
    """The model if it has active effects (closed forms do not apply), else None."""
    m = model_or_params if isinstance(model_or_params, DrumModel) else None
    return m if m is not None and m.has_effects else None


def _margin_function(model: DrumModel, hand_force_N, grade_pct, direction, occupants, mu_drum, gap_m,
                     initial_temp_C):
    from rollaway.hold.numeric import MarginFunction
    g, sign = _effective(grade_pct, direction)
    t_req = required_torque(model.params, g, occupants)
    return MarginFunction(model, validate_hand_force(hand_force_N), sign, t_req, mu_drum, gap_m, initial_temp_C)


def total_mass_kg(params: Model, occupants: ArrayLike = 1) -> np.ndarray:
    params = _params(params)
    return vehicle.vehicle_mass_kg(params.vehicle_mass_kg, validate_occupants(occupants), params.occupant_mass_kg)


def required_torque(params: BrakeParameters, grade_pct: ArrayLike, occupants: ArrayLike = 1) -> np.ndarray:
    """T_req at the rear axle, eq. (23) [N·m] (|grade| used)."""
    params = _params(params)
    g = np.abs(validate_grade(grade_pct))
    return vehicle.required_torque_Nm(total_mass_kg(params, occupants), g, params.wheel_radius_m,
                                      params.gravity_m_s2)


def tyre_adhesion_margin(params: BrakeParameters, grade_pct: ArrayLike, direction="downhill",
                         occupants: ArrayLike = 1, tyre_road_mu: ArrayLike | None = None) -> np.ndarray:
    """μ_r·N_r / (m g sin θ): ≥ 1 when the rear tyres can carry the slope force (inf on the flat)."""
    params = _params(params)
    g, sign = _effective(grade_pct, direction)
    n = validate_occupants(occupants)
    m = total_mass_kg(params, n)
    x, z = vehicle.centre_of_gravity_m(
        n, vehicle_mass_kg_=params.vehicle_mass_kg, occupant_mass_kg=params.occupant_mass_kg,
        cg_behind_front_m=params.cg_behind_front_m, cg_height_m=params.cg_height_m,
        front_seat_behind_front_m=params.front_seat_behind_front_m,
        rear_seat_behind_front_m=params.rear_seat_behind_front_m, seat_height_m=params.seat_height_m)
    n_r = vehicle.rear_axle_load_N(m, g, sign, wheelbase_m=params.wheelbase_m, cg_behind_front_m=x,
                                   cg_height_m=z, gravity_m_s2=params.gravity_m_s2)
    mu_r = params.tyre_road_mu if tyre_road_mu is None else np.asarray(tyre_road_mu, float)
    demand = vehicle.slope_force_N(m, g, params.gravity_m_s2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):   # a grade near 0: margin → inf
        return np.where(demand > 0, mu_r * n_r / np.where(demand > 0, demand, 1.0), np.inf)


def hold_margin(params: BrakeParameters, time_s: ArrayLike, hand_force_N: ArrayLike, grade_pct: ArrayLike,
                direction="downhill", occupants: ArrayLike = 1, mu_drum=None, gap_m=None,
                initial_temp_C=None) -> np.ndarray:
    """Brake hold margin 2·T_gen(t)/T_req over time (inf on the flat or for a self-locked shoe)."""
    g, sign = _effective(grade_pct, direction)
    series = as_model(params).evaluate(time_s, validate_hand_force(hand_force_N), sign, mu_drum=mu_drum, gap_m=gap_m,
                                       initial_temp_C=initial_temp_C)
    t_req = required_torque(params, g, occupants)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t_req > 0, 2.0 * series.torque_Nm / np.where(t_req > 0, t_req, 1.0), np.inf)


def min_brake_margin(params: BrakeParameters, hand_force_N: ArrayLike, grade_pct: ArrayLike, direction="downhill",
                     occupants: ArrayLike = 1, duration_s: ArrayLike = 300.0, mu_drum=None, gap_m=None,
                     initial_temp_C=None) -> np.ndarray:
    """Least brake hold margin over [0, duration_s].

    Eq. (16) is affine in ΔT and ΔT(t) of eq. (10) is monotone, so the torque is monotone in
    time and the least margin is at t = 0 or t = duration_s (no sampling needed).
    """
    model = _numeric(params)
    if model is not None:
        from rollaway.hold.numeric import least_margin
        fn = _margin_function(model, hand_force_N, grade_pct, direction, occupants, mu_drum, gap_m, initial_temp_C)
        shape = np.broadcast_shapes(fn.shape, np.shape(duration_s))
        return least_margin(fn, np.broadcast_to(duration_s, fn.shape).ravel()).reshape(shape)
    args = (hand_force_N, grade_pct, direction, occupants, mu_drum, gap_m, initial_temp_C)
    return np.minimum(hold_margin(params, 0.0, *args), hold_margin(params, duration_s, *args))


def _force_coefficients(params, gap_m):
    """F_l0 = k_u·u_6 + k_T·ΔT (eq. 16 is affine in u_6 and ΔT): return (k_u, k_T)."""
    f00 = unenergised_force(params, 0.0, 0.0, gap_m)
    k_u = unenergised_force(params, 1.0, 0.0, gap_m) - f00
    k_t = unenergised_force(params, 0.0, 1.0, gap_m) - f00
    return k_u, k_t


def time_to_slip_s(params: BrakeParameters, hand_force_N: ArrayLike, grade_pct: ArrayLike, direction="downhill",
                   occupants: ArrayLike = 1, mu_drum=None, gap_m=None, initial_temp_C=None,
                   horizon_s: float = np.inf) -> np.ndarray:
    """Time at which the brake hold margin first falls below 1 [s].

    0 if it never held, NaN if it holds up to *horizon_s* (and for ever if the drum
    cools towards a holding state).  Solved in closed form: eq. (16) is affine in ΔT,
    eq. (10) inverts to t = −τ ln((T* − T_amb)/(T_0 − T_amb)).  With effects: numeric, up to
    *horizon_s* (or :data:`NUMERIC_HORIZON_S`).
    """
    model = _numeric(params)
    if model is not None:
        from rollaway.hold.numeric import first_slip_time
        fn = _margin_function(model, hand_force_N, grade_pct, direction, occupants, mu_drum, gap_m, initial_temp_C)
        horizon = np.where(np.isfinite(horizon_s), horizon_s, NUMERIC_HORIZON_S)
        return first_slip_time(fn, np.broadcast_to(horizon, fn.shape).ravel()).reshape(fn.shape)
    params = _params(params)
    g, sign = _effective(grade_pct, direction)
    f = validate_hand_force(hand_force_N)
    mu = params.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
    t0 = params.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
    k_u, k_t = _force_coefficients(params, gap_m)
    u6 = drum_phys.lining_displacement_m(f, params.u6_slope_m_per_N, params.u6_offset_m)
    factor = shoe_factor(params, _direction_of(sign), mu)
    t_req = required_torque(params, g, occupants)
    with np.errstate(divide="ignore", invalid="ignore"):
        f_need = t_req / (2.0 * mu * params.drum_radius_m * factor)          # F_l0 needed (0 if locked)
        dT_star = (f_need - k_u * u6) / k_t                                    # ΔT at which F_l0 = f_need
        ratio = (t0 + dT_star - params.ambient_temp_C) / (t0 - params.ambient_temp_C)
        tau = params.cooling_time_constant_s
        t_cross = np.where((ratio > 0) & (ratio <= 1), -tau * np.log(np.where(ratio > 0, ratio, 1.0)), np.nan)
    m0 = hold_margin(params, 0.0, f, g, _direction_of(sign), occupants, mu, gap_m, t0)
    # while cooling from above ambient ΔT falls; the margin falls if k_t > 0
    falling = (k_t > 0) == (np.asarray(t0) > params.ambient_temp_C)
    out = np.where(m0 < 1.0, 0.0, np.where(falling, t_cross, np.nan))
    out = np.where(out > horizon_s, np.nan, out)
    return np.asarray(out, float)


def minimum_hand_force_N(params: BrakeParameters, grade_pct: ArrayLike, direction="downhill",
                         occupants: ArrayLike = 1, duration_s: ArrayLike = 300.0, mu_drum=None, gap_m=None,
                         initial_temp_C=None) -> np.ndarray:
    """Least hand force whose brake margin stays ≥ 1 over [0, duration_s] [N].

    Solved, not scanned: F_l0 is affine in u_6 (eq. 16), u_6 affine in F_hb (eq. 24),
    ΔT(t) monotone (eq. 10), so the worst instant is t = 0 or t = duration.  The tyre
    condition does not depend on hand force; check it with :func:`tyre_adhesion_margin`.
    Returns 0 if no force is needed, ``inf`` if no force can hold (μ_d = 0).  With effects:
    numeric root of the least margin in the hand force.
    """
    model = _numeric(params)
    if model is not None:
        from rollaway.hold.numeric import least_hand_force
        fn = _margin_function(model, 0.0, grade_pct, direction, occupants, mu_drum, gap_m, initial_temp_C)
        shape = np.broadcast_shapes(fn.shape, np.shape(duration_s))
        return least_hand_force(fn, np.broadcast_to(duration_s, fn.shape).ravel()).reshape(shape)
    params = _params(params)
    g, sign = _effective(grade_pct, direction)
    mu = params.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
    t0 = params.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
    k_u, k_t = _force_coefficients(params, gap_m)
    factor = shoe_factor(params, _direction_of(sign), mu)
    t_req = required_torque(params, g, occupants)
    dT_end = drum_temperature(params, duration_s, t0) - t0
    worst = np.minimum(0.0, k_t * dT_end)                 # most negative thermal term over the hold
    with np.errstate(divide="ignore", invalid="ignore"):
        f_need = np.where(mu > 0, t_req / (2.0 * np.where(mu > 0, mu, 1.0) * params.drum_radius_m * factor), np.inf)
        u6_need = (f_need - worst) / k_u
        force = (u6_need - params.u6_offset_m) / params.u6_slope_m_per_N
    force = np.where(t_req <= 0, 0.0, force)
    return np.maximum(force, 0.0)


def self_locking(params: Model, grade_pct: ArrayLike, direction="downhill", mu_drum=None) -> np.ndarray:
    """True where the shoe self-locks (l_f − s·μ_d·l_fr ≤ 0, eqs. 18–21): the 1D model has no finite torque."""
    p = _params(params)
    _, sign = _effective(grade_pct, direction)
    mu = p.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
    return np.isinf(shoe_factor(p, _direction_of(sign), mu))
