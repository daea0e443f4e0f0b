"""The drum chain: from the hand force on the lever to the torque at the wheel, one step after another.

Every function takes a :class:`~rollaway.model.drum_model.DrumModel` (its parameter set, effects and their
values) and broadcasts over its inputs (numpy rules).  Calibrated brake parameters
(:data:`CHAIN_OVERRIDES`, :mod:`rollaway.model.drum_parameters`) may be given per call in *values*,
as arrays for uncertainty draws.

Follow ``hand_force_N`` through :func:`evaluate`:

1. drum temperature T_d(t), eq. (10) (cooling law)            hook ``drum_temperature``
2. lining temperature T_l(t) (= T_d in the paper)             hook ``lining_temperature``
3. lining displacement u_6 from the hand force, eq. (24)      hook ``displacement``
4. lining modulus E_l and installation gap l_g (eq. 16)       hooks ``lining_modulus``, ``gap``
5. clamp force F_l0 before self-energising, eq. (16a/b)       hook ``clamp_force``
6. friction coefficient μ_d                                   hook ``friction``
7. self-energising factor, eqs. (18)–(21); F_l = F_l0 · factor
8. brake torque T_gen = μ_d · F_l · r_d, eq. (17b)            hook ``torque`` (e.g. a transducer offset)

With no effect away from its neutral values the chain runs exactly the paper's functions
in the paper's order (bit-identical to the baseline).  Everything broadcasts (numpy rules):
pass arrays of time, hand force, direction, μ_d, T_0 — or of effect values — and get arrays back.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from rollaway.effects.base import ModelState
from rollaway.effects.hooks import call_hook
from rollaway.physics import cooling, drum

# Calibrated brake parameters a call may override through *values* (μ_d and h have their own arguments)
CHAIN_OVERRIDES = ("u6_slope_m_per_N", "u6_offset_m", "shoe_arm_ratio", "ambient_temp_C", "gap_m")


@dataclass(frozen=True)
class BrakeSeries:
    """Time series of one drum (arrays broadcast to a common shape)."""

    time_s: np.ndarray
    drum_temp_C: np.ndarray
    normal_force_N: np.ndarray
    torque_Nm: np.ndarray
    self_locked: np.ndarray   # True where l_f − s·μ_d·l_fr ≤ 0 (eqs. 18–21): torque is unbounded
    lining_temp_C: np.ndarray | None = None   # what the lining feels (= drum_temp_C without effects)

    def columns(self) -> dict[str, np.ndarray]:
        return {"time_s": self.time_s, "drum_temp_C": self.drum_temp_C,
                "normal_force_N": self.normal_force_N, "torque_Nm": self.torque_Nm}


def _broadcast(a, shape) -> np.ndarray:
    """``np.broadcast_to(a, shape)`` (read-only, the same values), without its overhead where *a* has that
    shape already or is one number."""
    if type(a) is np.ndarray and (a.shape == shape or a.ndim == 0):
        v = a.view() if a.ndim else np.full(shape, a, a.dtype)
        v.setflags(write=False)
        return v
    return np.broadcast_to(a, shape)


def _common_shape(*shapes) -> tuple:
    """``np.broadcast_shapes(*shapes)``, at once where the shapes other than ``()`` are all the same."""
    shaped = {s for s in shapes if s != ()}
    if len(shaped) <= 1:
        return shaped.pop() if shaped else ()
    return np.broadcast_shapes(*shapes)


def direction_to_sign(direction) -> np.ndarray:
    """+1 facing downhill (eq. 18), −1 uphill (eq. 19); accepts names or numeric signs."""
    d = np.asarray(direction)
    if d.dtype == np.float64:          # the fits' case: signs already (the same numbers, without a copy)
        return np.where(d < 0, -1.0, 1.0)
    if d.dtype.kind in "biuf":
        return np.where(d.astype(float) < 0, -1.0, 1.0)
    return drum.direction_sign(direction)


def model_state(model, time_s, hand_force_N, direction="downhill", *, mu_drum=None, initial_temp_C=None,
          ambient_C=None, heat_transfer_W_m2K=None, test_index=None, test_ids=None) -> ModelState:
    """Inputs of the chain broadcast to one shape, as the effect hooks see them."""
    p = model.params
    sign = direction_to_sign(direction)
    mu = p.mu_drum if mu_drum is None else mu_drum
    t0 = p.initial_drum_temp_C if initial_temp_C is None else initial_temp_C
    amb = p.ambient_temp_C if ambient_C is None else ambient_C
    h = p.heat_transfer_W_m2K if heat_transfer_W_m2K is None else heat_transfer_W_m2K
    arrays = [np.asarray(x, float) for x in (time_s, hand_force_N, sign, t0, amb)]
    shape = _common_shape(*(a.shape for a in arrays), np.shape(mu), np.shape(h))
    t, f, s, t0b, ambb = (_broadcast(a, shape) for a in arrays)
    tid = None if test_index is None else _broadcast(np.asarray(test_index), shape)
    return ModelState(p, t, f, s, t0b, ambb, h, mu, test_index=tid, test_ids=test_ids)

def drum_temperature(model, time_s, *, initial_temp_C=None, ambient_C=None, heat_transfer_W_m2K=None,
                     values: dict | None = None, state: ModelState | None = None,
                     base_temp_C: ArrayLike | None = None, active: list | None = None, **state_kw) -> np.ndarray:
    """Drum temperature over time, eq. (10) plus the effects' ``drum_temperature`` hooks [°C].

    *base_temp_C*: the cooling law's temperature when it was integrated elsewhere (a logged,
    time-varying ambient, :func:`rollaway.physics.cooling.drum_temperature_logged_ambient_C`).
    *active*: ``model.active(values)`` when the caller has it already.
    """
    p = model.params
    t0 = p.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
    amb = p.ambient_temp_C if ambient_C is None else ambient_C
    h = p.heat_transfer_W_m2K if heat_transfer_W_m2K is None else heat_transfer_W_m2K
    tau = cooling.cooling_time_constant_s(p.drum_density_kg_m3, p.drum_specific_heat_J_kgK, p.drum_volume_m3,
                                          h, p.cooled_area_m2)
    temp = cooling.drum_temperature_C(time_s, t0, amb, tau) if base_temp_C is None else base_temp_C
    hooks = [(e, v) for e, v in (model.active(values) if active is None else active) if e.touches_temperature()]
    if not hooks:
        return temp
    st = state or model_state(model, time_s, state_kw.pop("hand_force_N", 0.0), state_kw.pop("direction", "downhill"),
                             initial_temp_C=t0, ambient_C=amb, heat_transfer_W_m2K=h, **state_kw)
    temp = _broadcast(temp, st.time_s.shape)
    for e, v in hooks:
        temp = call_hook(e, "drum_temperature", st, temp, v)
    return temp

def evaluate(model, time_s: ArrayLike, hand_force_N: ArrayLike, direction="downhill", *,
             mu_drum: ArrayLike | None = None, gap_m: ArrayLike | None = None,
             initial_temp_C: ArrayLike | None = None, ambient_C: ArrayLike | None = None,
             heat_transfer_W_m2K: ArrayLike | None = None, test_index: ArrayLike | None = None,
             values: dict | None = None, drum_temp_C: ArrayLike | None = None, test_ids=None) -> BrakeSeries:
    """The drum chain (module docstring, steps 1–8) for every element of the broadcast inputs.

    *direction*: ``"downhill"``/``"uphill"`` or numeric signs; *values*: effect values that
    override the model's for this call (fits); *drum_temp_C*: a drum temperature already
    computed with the same inputs (fits reuse the temperature channel).
    """
    brake = {k: np.asarray(values[k], float) for k in CHAIN_OVERRIDES if values and k in values}
    if ambient_C is None and "ambient_temp_C" in brake:
        ambient_C = brake["ambient_temp_C"]
    if gap_m is None and "gap_m" in brake:
        gap_m = brake["gap_m"]
    active = model.active(values)
    if not active:
        return _baseline(model, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
                              heat_transfer_W_m2K, drum_temp_C, brake)
    return _with_effects(model, active, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C,
                              ambient_C, heat_transfer_W_m2K, test_index, values, drum_temp_C, test_ids, brake)

def _lever(model, hand_force_N, brake: dict):
    """u_6 from the hand force, eq. (24), and the friction arm l_fr, with calibrated overrides in *brake*."""
    p = model.params
    u6 = drum.lining_displacement_m(hand_force_N, brake.get("u6_slope_m_per_N", p.u6_slope_m_per_N),
                                    brake.get("u6_offset_m", p.u6_offset_m))                  # eq. (24)
    arm = p.shoe_arm_friction_m if "shoe_arm_ratio" not in brake else brake["shoe_arm_ratio"] * p.shoe_arm_normal_m
    return u6, arm

def _baseline(model, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
              heat_transfer_W_m2K, drum_temp_C, brake=None) -> BrakeSeries:
    """The paper's chain, Ishak et al. 2018 eqs. (10), (16a/b), (17b), (18)–(21), (24)."""
    p = model.params
    mu = p.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
    t0 = p.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
    temp = (drum_temperature(model, time_s, initial_temp_C=t0, ambient_C=ambient_C,
                                  heat_transfer_W_m2K=heat_transfer_W_m2K)
            if drum_temp_C is None else np.asarray(drum_temp_C, float))
    dT = cooling.temperature_change_K(temp, t0)                                           # ΔT, eq. (16)
    u6, arm_friction_m = _lever(model, hand_force_N, brake or {})                          # eq. (24)
    f0 = unenergised_force(model, u6, dT, p.lining_modulus_Pa, p.gap_m if gap_m is None else np.asarray(gap_m, float))
    factor = drum.self_energising_factor(mu, direction_to_sign(direction), p.shoe_arm_normal_m,
                                         arm_friction_m)                               # eqs. (18)–(21)
    f_l = drum.normal_force_N(f0, factor)
    torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)                             # eq. (17b)
    shape = np.broadcast_shapes(np.shape(time_s), np.shape(temp), np.shape(f_l))
    b = lambda a: _broadcast(np.asarray(a, float), shape)  # noqa: E731
    return BrakeSeries(time_s=b(time_s), drum_temp_C=b(temp), normal_force_N=b(f_l), torque_Nm=b(torque),
                       self_locked=_broadcast(np.isinf(factor), shape), lining_temp_C=b(temp))

def unenergised_force(model, u6, dT, lining_modulus_Pa=None, gap_m=None):
    """Clamp force before self-energising, eq. (16a) (gap 0) or (16b), with the set's material values [N]."""
    p = model.params
    lining_modulus_Pa = p.lining_modulus_Pa if lining_modulus_Pa is None else lining_modulus_Pa
    gap_m = p.gap_m if gap_m is None else gap_m
    return drum.normal_force_unenergised_N(
        u6, dT, drum_area_m2=p.drum_area_m2, drum_modulus_Pa=p.drum_modulus_Pa, lining_area_m2=p.lining_area_m2,
        lining_modulus_Pa=lining_modulus_Pa, drum_expansion_per_K=p.drum_expansion_per_K,
        lining_expansion_per_K=p.lining_expansion_per_K, drum_thickness_m=p.drum_thickness_m,
        lining_thickness_m=p.lining_thickness_m, gap_m=gap_m)

def _with_effects(model, active, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
                  heat_transfer_W_m2K, test_index, values, drum_temp_C, test_ids=None, brake=None) -> BrakeSeries:
    p = model.params
    st = model_state(model, time_s, hand_force_N, direction, mu_drum=mu_drum, initial_temp_C=initial_temp_C,
                    ambient_C=ambient_C, heat_transfer_W_m2K=heat_transfer_W_m2K, test_index=test_index,
                    test_ids=test_ids)
    shape = st.time_s.shape
    for e, v in active:                       # effect values may be arrays (uncertainty draws)
        shape = _common_shape(shape, *(np.shape(x) for x in v.values()))
    shape = _common_shape(shape, *(np.shape(x) for x in (brake or {}).values()))   # so may calibrated ones
    if shape != st.time_s.shape:
        st = model_state(model, *(np.broadcast_to(a, shape) for a in (st.time_s, st.hand_force_N, st.sign)),
                        mu_drum=st.mu_drum, initial_temp_C=np.broadcast_to(st.initial_temp_C, shape),
                        ambient_C=np.broadcast_to(st.ambient_C, shape),
                        heat_transfer_W_m2K=st.heat_transfer_W_m2K,
                        test_index=None if st.test_index is None else np.broadcast_to(st.test_index, shape),
                        test_ids=test_ids)
    temp = (drum_temperature(model, st.time_s, initial_temp_C=st.initial_temp_C, ambient_C=st.ambient_C,
                                  heat_transfer_W_m2K=st.heat_transfer_W_m2K, values=values, state=st,
                                  active=active)
            if drum_temp_C is None else drum_temp_C)
    st.drum_temp_C = _broadcast(np.asarray(temp, float), shape)
    lining = st.drum_temp_C
    for e, v in active:                                                     # step 2
        lining = call_hook(e, "lining_temperature", st, lining, v)
    st.lining_temp_C = lining
    dT = cooling.temperature_change_K(st.drum_temp_C, st.initial_temp_C)   # ΔT of the drum, eq. (16)
    u6, arm_friction_m = _lever(model, st.hand_force_N, brake or {})         # eq. (24)
    modulus = p.lining_modulus_Pa
    gap = p.gap_m if gap_m is None else np.asarray(gap_m, float)
    for e, v in active:                                                     # steps 3–4
        u6 = call_hook(e, "displacement", st, u6, v)
        modulus = call_hook(e, "lining_modulus", st, modulus, v, scalar_ok=True)
        gap = call_hook(e, "gap", st, gap, v, scalar_ok=True)
    f0 = unenergised_force(model, u6, dT, modulus, gap)                            # step 5, eq. (16a/b)
    k_d = p.drum_area_m2 * p.drum_modulus_Pa
    k_l = p.lining_area_m2 * np.asarray(modulus)
    l_eff = p.lining_thickness_m + np.asarray(gap)
    den = k_l * p.drum_thickness_m + k_d * l_eff
    st.extra["series_stiffness_N_per_m"] = k_d * k_l / den
    if lining is not st.drum_temp_C:   # the lining's own thermal strain α_l·ΔT_l replaces α_l·ΔT_d (eq. 16)
        f0 = f0 + k_d * k_l * p.lining_expansion_per_K * l_eff * (lining - st.drum_temp_C) / den
    for e, v in active:
        f0 = call_hook(e, "clamp_force", st, f0, v)
    mu = _broadcast(np.asarray(st.mu_drum, float), shape)
    for e, v in active:                                                     # step 6
        mu = call_hook(e, "friction", st, mu, v)
    factor = drum.self_energising_factor(mu, st.sign, p.shoe_arm_normal_m, arm_friction_m)  # step 7
    f_l = drum.normal_force_N(f0, factor)
    torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)                 # step 8, eq. (17b)
    for e, v in active:
        torque = call_hook(e, "torque", st, torque, v)
    b = lambda a: _broadcast(np.asarray(a, float), shape)  # noqa: E731
    return BrakeSeries(time_s=b(st.time_s), drum_temp_C=b(st.drum_temp_C), normal_force_N=b(f_l),
                       torque_Nm=b(torque), self_locked=_broadcast(np.isinf(factor), shape),
                       lining_temp_C=b(lining))


__all__ = ["BrakeSeries", "CHAIN_OVERRIDES", "direction_to_sign", "drum_temperature", "evaluate", "model_state",
           "unenergised_force"]
