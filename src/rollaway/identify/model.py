"""The extended bench model: the paper's baseline plus effect hooks, over all samples at once.

Free baseline parameters are ``mu_drum`` (μ_d) and ``heat_transfer_W_m2K`` (h); effect
parameters are named ``"<effect>.<parameter>"``.  Per-test quantities are separate additions:
``"initial_temp_C"`` (each test's start temperature T_0, a nuisance parameter) and effect
parameters declared ``per_test``; in a values dict they hold one value per test (an array in
the order of ``data.tests``).  Without ``"initial_temp_C"`` the t = 0 readings are used.
A logged ambient that varies within a test is integrated through eq. (10)'s ODE
(:func:`rollaway.physics.cooling.drum_temperature_logged_ambient_C`).  With no effects (or all effects neutral)
the computation calls exactly the baseline functions of :mod:`rollaway.brake` and
:mod:`rollaway.physics` in the same order, so the result is bit-identical to
:func:`rollaway.brake.drum_brake`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.effects import Effect, ModelState, get_effect
from rollaway.identify.measurements import Measurements
from rollaway.parameters import BrakeParameters, load_parameters
from rollaway.physics import cooling, drum

BASELINE_FREE = ("mu_drum", "heat_transfer_W_m2K")
BASELINE_BOUNDS = {"mu_drum": (0.02, 1.0), "heat_transfer_W_m2K": (1.0, 400.0)}
BASELINE_UNITS = {"mu_drum": "–", "heat_transfer_W_m2K": "W/(m² K)"}
INITIAL_TEMP = "initial_temp_C"          # per-test nuisance: each test's T_0 [°C]
INITIAL_TEMP_BOUNDS = (-60.0, 1000.0)


@dataclass
class Prediction:
    drum_temp_C: np.ndarray
    lining_temp_C: np.ndarray
    normal_force_N: np.ndarray
    torque_Nm: np.ndarray


class BenchModel:
    """Baseline + a list of effects; :meth:`predict` evaluates it on measurements."""

    def __init__(self, params: BrakeParameters | str | None = None, effects=()):
        self.params = params if isinstance(params, BrakeParameters) else load_parameters(params)
        self.effects: list[Effect] = [get_effect(e) for e in effects]
        names = [e.name for e in self.effects]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            from rollaway.errors import UserError
            raise UserError(f"effect '{sorted(dup)[0]}' is given twice; name each effect once")

    # -- parameters ------------------------------------------------------------------
    def parameter_names(self) -> list[str]:
        """Global parameters (one value for all tests)."""
        return list(BASELINE_FREE) + [f"{e.name}.{p.name}" for e in self.effects for p in e.parameters
                                      if not p.per_test]

    def per_test_parameters(self) -> list[str]:
        """Parameters with one value per test: T_0 first, then per-test effect parameters."""
        return [INITIAL_TEMP] + [f"{e.name}.{p.name}" for e in self.effects for p in e.parameters if p.per_test]

    def initial_values(self) -> dict[str, float]:
        """Starting point of a fit: the set's μ_d and h, each effect parameter's ``initial``."""
        v = self.neutral_values()
        for e in self.effects:
            v.update({f"{e.name}.{p.name}": p.initial for p in e.parameters})
        return v

    def neutral_values(self) -> dict[str, float]:
        v = {"mu_drum": self.params.mu_drum, "heat_transfer_W_m2K": self.params.heat_transfer_W_m2K}
        for e in self.effects:
            v.update({f"{e.name}.{k}": x for k, x in e.neutral_values().items()})
        return v

    def bounds(self, name: str) -> tuple[float, float]:
        if name == INITIAL_TEMP:
            return INITIAL_TEMP_BOUNDS
        if name in BASELINE_BOUNDS:
            lo, hi = BASELINE_BOUNDS[name]
            if name == "mu_drum":   # never let the fit enter the self-locking region (eqs. 18–21)
                p = self.params
                hi = min(hi, 0.95 * p.shoe_arm_normal_m / max(p.shoe_arm_friction_m, 1e-12))
            return lo, hi
        eff, par = name.split(".", 1)
        spec = self._effect(eff).parameter(par)
        return spec.lower, spec.upper

    def unit(self, name: str) -> str:
        if name == INITIAL_TEMP:
            return "°C"
        if name in BASELINE_UNITS:
            return BASELINE_UNITS[name]
        eff, par = name.split(".", 1)
        return self._effect(eff).parameter(par).unit

    def _effect(self, name: str) -> Effect:
        for e in self.effects:
            if e.name == name:
                return e
        raise KeyError(name)

    def temperature_parameters(self) -> list[str]:
        """Parameters of the drum-temperature channel (h and temperature-changing effects)."""
        return ["heat_transfer_W_m2K"] + [f"{e.name}.{p.name}" for e in self.effects if e.touches_temperature()
                                          for p in e.parameters if not p.per_test]

    def torque_parameters(self) -> list[str]:
        return ["mu_drum"] + [f"{e.name}.{p.name}" for e in self.effects if not e.touches_temperature()
                              for p in e.parameters if not p.per_test]

    # -- evaluation ------------------------------------------------------------------
    def _active(self, values: dict, data: Measurements | None = None) -> list[tuple[Effect, dict]]:
        out = []
        for e in self.effects:
            v = {}
            for p in e.parameters:
                x = values.get(f"{e.name}.{p.name}", p.neutral)
                v[p.name] = (per_sample(x, data) if p.per_test and data is not None else float(x))
            if not e.is_neutral(v):
                out.append((e, v))
        return out

    def state(self, data: Measurements, values: dict | None = None) -> ModelState:
        values = {**self.neutral_values(), **(values or {})}
        amb = self.params.ambient_temp_C if data.ambient_C is None else data.ambient_C
        t0 = data.initial_temp_C if values.get(INITIAL_TEMP) is None else per_sample(values[INITIAL_TEMP], data)
        return ModelState(self.params, data.time_s, data.hand_force_N, data.sign, t0, amb,
                          float(values["heat_transfer_W_m2K"]), float(values["mu_drum"]),
                          test_index=data.test_index, test_ids=data.tests)

    def drum_temperature(self, data: Measurements, values: dict | None = None,
                         state: ModelState | None = None) -> np.ndarray:
        """Measured channel: drum temperature, eq. (10) plus temperature hooks [°C]."""
        values = {**self.neutral_values(), **(values or {})}
        st = self.state(data, values) if state is None else state
        p = self.params
        tau = cooling.cooling_time_constant_s(p.drum_density_kg_m3, p.drum_specific_heat_J_kgK, p.drum_volume_m3,
                                              st.heat_transfer_W_m2K, p.cooled_area_m2)
        if ambient_varies(data):
            temp = cooling.drum_temperature_logged_ambient_C(st.time_s, st.initial_temp_C, st.ambient_C, tau,
                                                             data.test_index)
        else:
            temp = cooling.drum_temperature_C(st.time_s, st.initial_temp_C, st.ambient_C, tau)
        for e, v in self._active(values, data):
            temp = e.drum_temperature(st, temp, v)
        return temp

    def predict(self, data: Measurements, values: dict | None = None,
                drum_temp_C: np.ndarray | None = None) -> Prediction:
        """Both channels for every sample; *drum_temp_C* reuses a temperature already computed."""
        values = {**self.neutral_values(), **(values or {})}
        active = self._active(values, data)
        p = self.params
        st = self.state(data, values)
        st.drum_temp_C = self.drum_temperature(data, values, st) if drum_temp_C is None else drum_temp_C
        lining = st.drum_temp_C
        for e, v in active:
            lining = e.lining_temperature(st, lining, v)
        st.lining_temp_C = lining
        dT = cooling.temperature_change_K(st.drum_temp_C, st.initial_temp_C)
        u6 = drum.lining_displacement_m(st.hand_force_N, p.u6_slope_m_per_N, p.u6_offset_m)
        modulus, gap = p.lining_modulus_Pa, p.gap_m
        for e, v in active:
            u6 = e.displacement(st, u6, v)
            modulus = e.lining_modulus(st, modulus, v)
            gap = e.gap(st, gap, v)
        f0 = drum.normal_force_unenergised_N(
            u6, dT, drum_area_m2=p.drum_area_m2, drum_modulus_Pa=p.drum_modulus_Pa, lining_area_m2=p.lining_area_m2,
            lining_modulus_Pa=modulus, drum_expansion_per_K=p.drum_expansion_per_K,
            lining_expansion_per_K=p.lining_expansion_per_K, drum_thickness_m=p.drum_thickness_m,
            lining_thickness_m=p.lining_thickness_m, gap_m=gap)
        if active:
            k_d = p.drum_area_m2 * p.drum_modulus_Pa
            k_l = p.lining_area_m2 * np.asarray(modulus)
            l_eff = p.lining_thickness_m + np.asarray(gap)
            den = k_l * p.drum_thickness_m + k_d * l_eff
            st.extra["series_stiffness_N_per_m"] = k_d * k_l / den
            if lining is not st.drum_temp_C:   # the lining's own thermal strain α_l·ΔT_l (eq. 16)
                f0 = f0 + k_d * k_l * p.lining_expansion_per_K * l_eff * (lining - st.drum_temp_C) / den
            for e, v in active:
                f0 = e.clamp_force(st, f0, v)
        mu = st.mu_drum
        for e, v in active:
            mu = e.friction(st, np.broadcast_to(np.asarray(mu, float), st.time_s.shape), v)
        factor = drum.self_energising_factor(mu, st.sign, p.shoe_arm_normal_m, p.shoe_arm_friction_m)
        f_l = drum.normal_force_N(f0, factor)
        torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)
        for e, v in active:
            torque = e.torque(st, torque, v)
        return Prediction(st.drum_temp_C, np.broadcast_to(lining, st.time_s.shape), f_l, torque)


def per_sample(value, data: Measurements) -> np.ndarray | float:
    """A per-test quantity (scalar, or one value per test in ``data.tests`` order) at every sample."""
    a = np.asarray(value, float)
    if a.ndim == 0:
        return float(a)
    if a.shape != (data.n_tests,):
        raise ValueError(f"per-test values: {a.shape[0]} given for {data.n_tests} tests")
    return a[data.test_index]


def ambient_varies(data: Measurements) -> bool:
    """True when a logged ambient changes within a test (then eq. 10's ODE is integrated)."""
    cached = getattr(data, "_ambient_varies", None)
    if cached is None:
        a = data.ambient_C
        if a is None:
            cached = False
        else:
            lo = np.full(data.n_tests, np.inf)
            hi = np.full(data.n_tests, -np.inf)
            np.minimum.at(lo, data.test_index, a)
            np.maximum.at(hi, data.test_index, a)
            cached = bool(np.any(hi > lo))
        data._ambient_varies = cached
    return cached
