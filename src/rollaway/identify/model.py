"""The model a calibration moves: the drum model's free values, evaluated on bench samples.

The chain itself is :class:`rollaway.model.DrumModel` (the same one the hold check, the
simulator and sweeps use); this class only maps the fit's free parameters — ``mu_drum``
(μ_d), ``heat_transfer_W_m2K`` (h) and ``"<effect>.<parameter>"`` — onto it and evaluates it
on all samples of all tests at once.  With no effects (or all effects neutral) the result is
bit-identical to :func:`rollaway.brake.drum_brake`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.effects import ModelState
from rollaway.identify.measurements import Measurements
from rollaway.model import BASELINE_BOUNDS, BASELINE_FREE, BASELINE_UNITS, DrumModel  # noqa: F401
from rollaway.parameters import BrakeParameters


@dataclass
class Prediction:
    drum_temp_C: np.ndarray
    lining_temp_C: np.ndarray
    normal_force_N: np.ndarray
    torque_Nm: np.ndarray


class BenchModel:
    """Free parameters of a :class:`DrumModel` and its evaluation on measurements."""

    def __init__(self, params: BrakeParameters | str | None = None, effects=()):
        self.drum = params if isinstance(params, DrumModel) else DrumModel(params, effects)
        self.params = self.drum.params
        self.effects = list(self.drum.effects)

    # -- parameters ------------------------------------------------------------------
    def parameter_names(self) -> list[str]:
        return list(BASELINE_FREE) + list(self.drum.neutral_values())

    def neutral_values(self) -> dict[str, float]:
        return {"mu_drum": self.params.mu_drum, "heat_transfer_W_m2K": self.params.heat_transfer_W_m2K,
                **self.drum.neutral_values()}

    def bounds(self, name: str) -> tuple[float, float]:
        return self.drum.bounds(name)

    def unit(self, name: str) -> str:
        return self.drum.unit(name)

    def temperature_parameters(self) -> list[str]:
        """Parameters of the drum-temperature channel (h and temperature-changing effects)."""
        return ["heat_transfer_W_m2K"] + [f"{e.name}.{p.name}" for e in self.effects if e.touches_temperature()
                                          for p in e.parameters]

    def torque_parameters(self) -> list[str]:
        return ["mu_drum"] + [f"{e.name}.{p.name}" for e in self.effects if not e.touches_temperature()
                              for p in e.parameters]

    # -- evaluation ------------------------------------------------------------------
    def _split(self, values: dict | None):
        values = {**self.neutral_values(), **(values or {})}
        effect_values = {k: float(v) for k, v in values.items() if k not in BASELINE_FREE}
        return values, effect_values

    def _inputs(self, data: Measurements, values: dict) -> dict:
        amb = self.params.ambient_temp_C if data.ambient_C is None else data.ambient_C
        return dict(initial_temp_C=data.initial_temp_C, ambient_C=amb,
                    heat_transfer_W_m2K=float(values["heat_transfer_W_m2K"]), test_index=data.test_index)

    def state(self, data: Measurements, values: dict | None = None) -> ModelState:
        values, _ = self._split(values)
        return self.drum.state(data.time_s, data.hand_force_N, data.sign, mu_drum=float(values["mu_drum"]),
                               **self._inputs(data, values))

    def drum_temperature(self, data: Measurements, values: dict | None = None,
                         state: ModelState | None = None) -> np.ndarray:
        """Measured channel: drum temperature, eq. (10) plus temperature hooks [°C]."""
        values, effect_values = self._split(values)
        kw = self._inputs(data, values)
        st = state if state is not None else (self.state(data, values) if self.drum.active(effect_values) else None)
        return self.drum.drum_temperature(data.time_s, initial_temp_C=kw["initial_temp_C"], ambient_C=kw["ambient_C"],
                                          heat_transfer_W_m2K=kw["heat_transfer_W_m2K"], values=effect_values,
                                          state=st)

    def predict(self, data: Measurements, values: dict | None = None,
                drum_temp_C: np.ndarray | None = None) -> Prediction:
        """Both channels for every sample; *drum_temp_C* reuses a temperature already computed."""
        values, effect_values = self._split(values)
        s = self.drum.evaluate(data.time_s, data.hand_force_N, data.sign, mu_drum=float(values["mu_drum"]),
                               values=effect_values, drum_temp_C=drum_temp_C, **self._inputs(data, values))
        return Prediction(s.drum_temp_C, s.lining_temp_C, s.normal_force_N, s.torque_Nm)

    def drum_model(self, values: dict | None = None, **kw) -> DrumModel:
        """The calibrated :class:`DrumModel` at *values* (μ_d and h go into the parameter set)."""
        values, effect_values = self._split(values)
        return DrumModel(self.params.replace(mu_drum=float(values["mu_drum"]),
                                             heat_transfer_W_m2K=float(values["heat_transfer_W_m2K"])),
                         self.effects, effect_values, **kw)
