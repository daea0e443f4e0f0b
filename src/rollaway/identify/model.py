"""The extended bench model: the paper's baseline plus effect hooks, over all samples at once.

Free brake parameters are a subset of :data:`rollaway.model.drum_parameters.BASELINE_FREE` (μ_d, the
eq. (24) slope and offset, the arm ratio l_fr/l_f, h, the ambient), chosen by a
:class:`DrumPlan` (default: μ_d and h); effect parameters are named ``"<effect>.<parameter>"``.  Per-test quantities are separate additions:
``"initial_temp_C"`` (each test's start temperature T_0, a nuisance parameter) and effect
parameters declared ``per_test``; in a values dict they hold one value per test (an array in
the order of ``data.tests``).  Without ``"initial_temp_C"`` the t = 0 readings are used.
A logged ambient that varies within a test is integrated through eq. (10)'s ODE
(:func:`rollaway.physics.cooling.drum_temperature_logged_ambient_C`).

The chain itself is :class:`rollaway.model.drum_model.DrumModel` (the one the hold check, the simulator
and sweeps use); this class maps the fit's values onto it and evaluates it on all samples of
all tests at once.  With no effects (or all effects neutral) the result is bit-identical to
:func:`rollaway.model.brake.drum_brake`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.effects import Effect, ModelState
from rollaway.bench.measurements import Measurements
from rollaway.model.drum_parameters import BASELINE_FREE, LEGACY_FREE, apply, values_of
from rollaway.model.drum_model import CHAIN_OVERRIDES, DrumModel
from rollaway.model.parameters import BrakeParameters
from rollaway.physics import cooling

INITIAL_TEMP = "initial_temp_C"          # per-test nuisance: each test's T_0 [°C]
INITIAL_TEMP_BOUNDS = (-60.0, 1000.0)
KEPT_TEMPERATURES = 4                    # drum temperatures a BenchModel keeps (:meth:`BenchModel.predict`)


@dataclass(frozen=True)
class DrumPlan:
    """A parameter set and which of its brake parameters a calibration frees (the rest stay at their values)."""

    params: BrakeParameters
    free: tuple[str, ...] = LEGACY_FREE

    def __post_init__(self):
        bad = [n for n in self.free if n not in BASELINE_FREE]
        if bad:
            raise ValueError(f"unknown brake parameter {bad[0]!r}; calibratable: {', '.join(BASELINE_FREE)}")
        object.__setattr__(self, "free", tuple(n for n in BASELINE_FREE if n in self.free))


@dataclass
class Prediction:
    drum_temp_C: np.ndarray
    lining_temp_C: np.ndarray
    normal_force_N: np.ndarray
    torque_Nm: np.ndarray


class BenchModel:
    """Baseline + a list of effects; :meth:`predict` evaluates it on measurements."""

    def __init__(self, params: BrakeParameters | DrumPlan | str | None = None, effects=()):
        self.free: tuple[str, ...] = LEGACY_FREE
        if isinstance(params, DrumPlan):
            self.free, params = params.free, params.params
        if not isinstance(params, (DrumModel, BrakeParameters)):   # a set name or file: its parameter set only,
            params = DrumModel(params).params                        # the effects fitted are the ones given
        self.drum = params if isinstance(params, DrumModel) else DrumModel(params, effects)
        self.params = self.drum.params
        self.effects: list[Effect] = list(self.drum.effects)

    # -- parameters ------------------------------------------------------------------
    def parameter_names(self) -> list[str]:
        """Global parameters (one value for all tests): the freed brake parameters, then the effects'."""
        return list(self.free) + [f"{e.name}.{p.name}" for e in self.effects for p in e.parameters
                                  if not p.per_test and not p.held]

    def per_test_parameters(self) -> list[str]:
        """Parameters with one value per test: T_0 first, then per-test effect parameters."""
        return [INITIAL_TEMP] + [f"{e.name}.{p.name}" for e in self.effects for p in e.parameters if p.per_test]

    def initial_values(self) -> dict[str, float]:
        """Starting point of a fit: the set's μ_d and h, each effect parameter's ``initial``."""
        v = self.neutral_values()
        for e in self.effects:
            v.update({f"{e.name}.{p.name}": p.initial for p in e.parameters if not p.held})
        return v

    def neutral_values(self) -> dict[str, float]:
        if getattr(self, "_neutral", None) is None:       # params and effects are set once, in __init__
            v = values_of(self.params)
            for e in self.effects:
                v.update({f"{e.name}.{k}": x for k, x in e.neutral_values().items()})
            self._neutral = v
        return dict(self._neutral)

    def bounds(self, name: str) -> tuple[float, float]:
        if name == INITIAL_TEMP:
            return INITIAL_TEMP_BOUNDS
        return self.drum.bounds(name)

    def unit(self, name: str) -> str:
        if name == INITIAL_TEMP:
            return "°C"
        return self.drum.unit(name)

    def temperature_parameters(self) -> list[str]:
        """Parameters of the drum-temperature channel (h and temperature-changing effects)."""
        from rollaway.model.drum_parameters import FREE_PARAMETERS
        return [n for n in self.free if FREE_PARAMETERS[n].channel == "temperature"] + [
            f"{e.name}.{p.name}" for e in self.effects if e.touches_temperature() for p in e.parameters
            if not p.per_test and not p.held]

    def torque_parameters(self) -> list[str]:
        from rollaway.model.drum_parameters import FREE_PARAMETERS
        return [n for n in self.free if FREE_PARAMETERS[n].channel == "torque"] + [
            f"{e.name}.{p.name}" for e in self.effects if not e.touches_temperature() for p in e.parameters
            if not p.per_test and not p.held]

    # -- evaluation ------------------------------------------------------------------
    def _active(self, values: dict, data: Measurements | None = None) -> list[tuple[Effect, dict]]:
        out = []
        for e in self.effects:
            v = {}
            for p in e.parameters:
                x = values.get(f"{e.name}.{p.name}", p.neutral)
                v[p.name] = _number(x, data) if data is not None else float(x)
            if not e.is_neutral(v):
                out.append((e, v))
        return out

    def state(self, data: Measurements, values: dict | None = None) -> ModelState:
        values = {**self.neutral_values(), **(values or {})}
        return self.drum.state(data.time_s, data.hand_force_N, data.sign, mu_drum=float(values["mu_drum"]),
                               **self._inputs(data, values))

    def _effect_values(self, values: dict, data: Measurements) -> dict:
        """Effect values for the chain (per-test ones expanded to every sample) and the brake overrides."""
        out = {k: _number(values[k], data) for k in CHAIN_OVERRIDES if k in values and k in self.free}
        for e in self.effects:
            for p in e.parameters:
                key = f"{e.name}.{p.name}"
                out[key] = _number(values.get(key, p.neutral), data)
        return out

    def _inputs(self, data: Measurements, values: dict) -> dict:
        amb = _number(values.get("ambient_temp_C", self.params.ambient_temp_C), data) if data.ambient_C is None \
            else data.ambient_C
        t0 = data.initial_temp_C if values.get(INITIAL_TEMP) is None else per_sample(values[INITIAL_TEMP], data)
        return dict(initial_temp_C=t0, ambient_C=amb, heat_transfer_W_m2K=_number(values["heat_transfer_W_m2K"], data),
                    test_index=data.test_index, test_ids=data.tests)

    def drum_temperature(self, data: Measurements, values: dict | None = None,
                         state: ModelState | None = None) -> np.ndarray:
        """Measured channel: drum temperature, eq. (10) (through a logged ambient if it varies) plus hooks [°C]."""
        values = {**self.neutral_values(), **(values or {})}
        kw = self._inputs(data, values)
        base = None
        if ambient_varies(data):
            p = self.params
            tau = cooling.cooling_time_constant_s(p.drum_density_kg_m3, p.drum_specific_heat_J_kgK, p.drum_volume_m3,
                                                  kw["heat_transfer_W_m2K"], p.cooled_area_m2)
            base = cooling.drum_temperature_logged_ambient_C(data.time_s, kw["initial_temp_C"], kw["ambient_C"], tau,
                                                             data.test_index)
        return self.drum.drum_temperature(data.time_s, values=self._effect_values(values, data), state=state,
                                          base_temp_C=base, hand_force_N=data.hand_force_N, direction=data.sign,
                                          **kw)

    def predict(self, data: Measurements, values: dict | None = None,
                drum_temp_C: np.ndarray | None = None) -> Prediction:
        """Both channels for every sample; *drum_temp_C* reuses a temperature already computed."""
        values = {**self.neutral_values(), **(values or {})}
        if drum_temp_C is None and (ambient_varies(data) or self._temperature_effects()):
            drum_temp_C = self._kept_temperature(data, values)
        s = self.drum.evaluate(data.time_s, data.hand_force_N, data.sign, mu_drum=_number(values["mu_drum"], data),
                               values=self._effect_values(values, data), drum_temp_C=drum_temp_C,
                               **self._inputs(data, values))
        return Prediction(s.drum_temp_C, s.lining_temp_C, s.normal_force_N, s.torque_Nm)

    def _temperature_effects(self) -> list[Effect]:
        """The effects whose hooks change the drum temperature."""
        if getattr(self, "_temp_effects", None) is None:
            self._temp_effects = [e for e in self.effects if e.touches_temperature()]
        return self._temp_effects

    def _kept_temperature(self, data: Measurements, values: dict) -> np.ndarray:
        """:meth:`drum_temperature`, the last :data:`KEPT_TEMPERATURES` answers kept per data set: the torque
        channel's parameters (μ_d, the torque effects', most of a fit's Jacobian columns) leave the temperature
        unchanged, and a radiating drum or a logged ambient makes it the costly part of a prediction.  The key is
        every value the temperature reads: T_0, h, the ambient and the temperature effects' parameters (the other
        chain overrides act on the torque only).  The answer is read-only."""
        parts = [values.get(INITIAL_TEMP), values.get("heat_transfer_W_m2K"), values.get("ambient_temp_C")]
        parts += [values.get(f"{e.name}.{p.name}", p.neutral) for e in self._temperature_effects()
                  for p in e.parameters]
        key = tuple((None if x is None else (np.shape(x), np.asarray(x, float).tobytes())) for x in parts)
        kept = self.__dict__.setdefault("_kept", [])
        for i, (d, k, temp) in enumerate(kept):
            if d is data and k == key:
                kept.insert(0, kept.pop(i))
                return temp
        temp = np.array(self.drum_temperature(data, values), float)
        temp.flags.writeable = False
        kept.insert(0, (data, key, temp))
        del kept[KEPT_TEMPERATURES:]
        return temp

    def drum_model(self, values: dict | None = None, **kw) -> DrumModel:
        """The calibrated :class:`DrumModel` at *values* (μ_d and h go into the parameter set).

        Per-test values (T_0, per-test effect parameters) describe the bench's tests, not the car:
        they are left out (per-test effect parameters at their neutral values).
        """
        values = {**self.neutral_values(), **(values or {})}
        effect_values = {f"{e.name}.{p.name}": float(values.get(f"{e.name}.{p.name}", p.neutral))
                         for e in self.effects for p in e.parameters if not p.per_test}
        params = apply(self.params, {k: values[k] for k in BASELINE_FREE if k in values})
        return DrumModel(params.replace(), self.effects, effect_values, **kw)


def per_sample(value, data: Measurements) -> np.ndarray | float:
    """A per-test quantity (scalar, or one value per test in ``data.tests`` order) at every sample."""
    a = np.asarray(value, float)
    if a.ndim == 0:
        return float(a)
    if a.shape != (data.n_tests,):
        raise ValueError(f"per-test values: {a.shape[0]} given for {data.n_tests} tests")
    return a[data.test_index]


def _number(value, data: Measurements) -> np.ndarray | float:
    """A parameter's value for the chain: one number, or one per test (per-test parameters; globals of several
    value sets evaluated at once on stacked copies of the data) expanded to every sample."""
    if isinstance(value, float):      # the common case (numpy's float64 too), without numpy's dispatch
        return float(value)
    return float(value) if np.ndim(value) == 0 else per_sample(value, data)


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
