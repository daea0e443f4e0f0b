"""The drum model: ONE chain from hand force to brake torque, with optional physical effects.

:class:`DrumModel` = a parameter set (:class:`~rollaway.model.parameters.BrakeParameters`) +
effects (:mod:`rollaway.effects`, the catalogue or plugins) + the effects' values, and,
for a model calibrated on bench data, the covariance of the fitted parameters and where
they came from.  Every part of rollaway evaluates the drum through :meth:`DrumModel.evaluate`:
the analytic hold check (:mod:`rollaway.hold`), the MuJoCo brake callback, sweeps, figures
and the fits of :mod:`rollaway.identify`.

Follow ``hand_force_N`` from the lever to the wheel in :mod:`rollaway.model.chain` (eqs. 10, 16–24,
each step with its effect hook); :meth:`DrumModel.evaluate` runs it.  This module holds what a
model *is*: its set, effects, values, bounds of what a calibration may move, and the copies with
other values that uncertainty draws and fits make.
"""
from __future__ import annotations

from dataclasses import fields
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from rollaway.model import chain
from rollaway.model.chain import CHAIN_OVERRIDES, BrakeSeries, direction_to_sign  # noqa: F401  (re-exported)
from rollaway.model.covariance import Covariance
from rollaway.model.drum_parameters import BASELINE_BOUNDS, BASELINE_FREE, BASELINE_UNITS, apply, values_of
from rollaway.effects.base import Effect, ModelState
from rollaway.errors import UserError
from rollaway.model.parameters import BrakeParameters

_PARAMETER_NAMES = frozenset(f.name for f in fields(BrakeParameters)) | {"cooling_time_constant_s"}

class DrumModel:
    """The drum brake: a parameter set + effects + effect values (+ covariance and provenance when calibrated).

    Parameters
    ----------
    params : str or path-like or BrakeParameters, default "paper"
        A parameter-set name (``"paper"``), a parameter file, or a model file (``.toml``, e.g. one
        written by ``Diagnosis.save_model``): a model file brings its effects, fitted values,
        covariance and provenance with it.
    effects : sequence of str or Effect, optional
        Physical effects added to the paper's chain (``rollaway.identify.available_effects()``
        lists them: ``lining_creep``, ``friction_temperature``, ...), after a file's own.
    values : dict, optional
        ``{"effect.parameter": value}`` in the parameter's unit (e.g. ``{"lining_creep.relaxed_fraction":
        0.12}``); missing ones are the effect's neutral value (no change).  Overrides a file's.
    covariance : Covariance, optional
        Covariance of fitted values (``mu_drum``, ``heat_transfer_W_m2K``, ``effect.parameter``), for
        ``rollaway.hold(..., uncertainty=N)``.

    Attributes
    ----------
    params : BrakeParameters
        The parameter set; its values read through the model too (``model.mu_drum`` [–]).  The
        baseline values μ_d and h live here.
    effects : tuple of Effect
    values : dict
        Every effect parameter's value, neutral ones included.

    Examples
    --------
    >>> m = rollaway.DrumModel("paper", effects=["lining_creep"], values={"lining_creep.relaxed_fraction": 0.12})
    >>> s = m.evaluate(time_s=[0, 1800, 3600], hand_force_N=300, direction="uphill")
    >>> s.torque_Nm                                       # per drum [N·m]        # doctest: +SKIP
    """

    def __init__(self, params: BrakeParameters | str | Path | None = "paper", effects=(), values: dict | None = None, *,
                 covariance: Covariance | None = None, provenance: dict | None = None, name: str | None = None,
                 base: str | None = None, effect_files: dict | None = None, calibration: dict | None = None,
                 predictive: dict | None = None, alternatives: list | None = None):
        from rollaway.effects import get_effect

        if not isinstance(params, BrakeParameters):     # a set name, parameter file or model file
            from rollaway.model.model_file import read_model
            parts = read_model(params)
            params, effects = parts["params"], (*parts["effects"], *effects)
            values = {**parts["values"], **(values or {})}
            covariance = parts["covariance"] if covariance is None else covariance
            provenance = parts["provenance"] if provenance is None else provenance
            name, base = name or parts["name"], base or parts["base"]
            effect_files = {**parts["effect_files"], **(effect_files or {})}
            calibration = parts["calibration"] if calibration is None else calibration
            predictive = parts["predictive"] if predictive is None else predictive
        self.params = params
        self.effects: tuple[Effect, ...] = tuple(get_effect(e) for e in effects)
        names = [e.name for e in self.effects]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise UserError(f"effect '{dup[0]}' is given twice; name each effect once")
        full = self.neutral_values()
        for key, v in (values or {}).items():
            if key not in full:
                raise UserError(f"model values: unknown effect parameter '{key}'; the model's effect parameters are: "
                                + (", ".join(full) or "none (no effects)"))
            full[key] = v
        self.values: dict[str, float] = full
        self.covariance = covariance
        self.provenance = dict(provenance or {})
        self.name = name or (self.params.name + "".join(" + " + n for n in names))
        self.base = base or "paper"              # named set the parameters extend (model files)
        self.effect_files = dict(effect_files or {})   # effect name -> plugin file it came from
        self.calibration: dict[str, str] = dict(calibration or {})   # brake parameter -> what the bench data said
        self.predictive: dict = dict(predictive or {})    # model error, tested range (rollaway.uncertainty.predictive)
        self._alternatives = alternatives                 # [(weight, DrumModel)] competing effect sets

    # -- bookkeeping -------------------------------------------------------------------
    def __getattr__(self, name: str):
        """Parameter values read through the model (``model.mu_drum`` is its set's μ_d)."""
        if name in _PARAMETER_NAMES:
            return getattr(self.params, name)
        raise AttributeError(f"'DrumModel' object has no attribute '{name}'")

    def __repr__(self) -> str:
        active = [e.name for e, _ in self.active()]
        return f"DrumModel({self.params.name!r}, effects={active})"

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import result_html
        rows = {"μ_d": self.params.mu_drum, "h [W/(m² K)]": self.params.heat_transfer_W_m2K, **self.values}
        if self.covariance is not None:
            rows.update({f"σ {k}": v for k, v in self.covariance.stderr.items()})
        return result_html(f"drum model {self.name}", rows)

    @property
    def alternatives(self) -> list[tuple[float, "DrumModel"]]:
        """Competing effect sets the bench data could not rule out, with their weights (the model itself
        keeps 1 − Σ weights); loaded from the files the model file names."""
        if self._alternatives is None:
            self._alternatives = [(a["weight"], DrumModel(a["file"])) for a in self.predictive.get("alternatives", [])]
        return self._alternatives

    def neutral_values(self) -> dict[str, float]:
        return {f"{e.name}.{p.name}": p.neutral for e in self.effects for p in e.parameters}

    def effect_values(self, effect: str) -> dict[str, float]:
        return {k.split(".", 1)[1]: v for k, v in self.values.items() if k.split(".", 1)[0] == effect}

    def active(self, values: dict | None = None) -> list[tuple[Effect, dict]]:
        """The effects whose values are not all neutral, each with its parameter dict."""
        vals = self.values if values is None else {**self.values, **values}
        out = []
        for e in self.effects:
            v = {p.name: vals.get(f"{e.name}.{p.name}", p.neutral) for p in e.parameters}
            if not _all_neutral(e, v):
                out.append((e, v))
        return out

    @property
    def has_effects(self) -> bool:
        """True if any effect changes the paper's chain (the closed-form hold check no longer applies)."""
        return bool(self.active())

    def with_params(self, params: BrakeParameters) -> "DrumModel":
        return self._copy(params=params)

    def replace_params(self, **changes) -> "DrumModel":
        return self.with_params(self.params.replace(**changes))

    def with_values(self, values: dict) -> "DrumModel":
        return self._copy(values={**self.values, **values})

    def _copy(self, **kw) -> "DrumModel":
        args = dict(params=self.params, effects=self.effects, values=self.values, covariance=self.covariance,
                    provenance=self.provenance, base=self.base, effect_files=self.effect_files,
                    calibration=self.calibration, predictive=self.predictive, alternatives=self._alternatives)
        same_name = self.name == (self.params.name + "".join(" + " + e.name for e in self.effects))
        args.update(kw)
        return DrumModel(**args, name=None if same_name else self.name)

    def fitted_values(self) -> dict[str, float]:
        """Every value a calibration may move: the brake parameters (:mod:`rollaway.model.drum_parameters`) and
        the effects' parameters."""
        return {**values_of(self.params), **self.values}

    def bounds(self, name: str) -> tuple[float, float]:
        """Physical bounds of a free parameter (baseline or ``effect.parameter``)."""
        if name in BASELINE_BOUNDS:
            lo, hi = BASELINE_BOUNDS[name]
            p = self.params
            if name == "mu_drum":   # never enter the self-locking region (eqs. 18–21)
                hi = min(hi, 0.95 * p.shoe_arm_normal_m / max(p.shoe_arm_friction_m, 1e-12))
            elif name == "shoe_arm_ratio":
                hi = min(hi, 0.95 / max(p.mu_drum, 1e-12))
            return lo, hi
        eff, par = name.split(".", 1)
        spec = self.effect(eff).parameter(par)
        return spec.lower, spec.upper

    def unit(self, name: str) -> str:
        if name in BASELINE_UNITS:
            return BASELINE_UNITS[name]
        eff, par = name.split(".", 1)
        return self.effect(eff).parameter(par).unit

    def effect(self, name: str) -> Effect:
        for e in self.effects:
            if e.name == name:
                return e
        raise UserError(f"the model has no effect '{name}'; its effects are: "
                        + (", ".join(e.name for e in self.effects) or "none"))

    def with_draw(self, draw: dict) -> "DrumModel":
        """This model with some fitted values replaced (brake parameters such as ``mu_drum``, effect values)."""
        base = {k: v for k, v in draw.items() if k in BASELINE_FREE}
        eff = {k: v for k, v in draw.items() if k not in BASELINE_FREE}
        out = self.with_params(apply(self.params, base)) if base else self
        return out.with_values(eff) if eff else out

    # -- the chain: rollaway.model.chain, step by step --------------------------------------------
    def state(self, time_s, hand_force_N, direction="downhill", **kw) -> ModelState:
        """Inputs of the chain broadcast to one shape, as the effect hooks see them (:func:`rollaway.model.chain.model_state`)."""
        return chain.model_state(self, time_s, hand_force_N, direction, **kw)

    def drum_temperature(self, time_s, **kw) -> np.ndarray:
        """Drum temperature, eq. (10) plus the effects' hooks [°C] (:func:`rollaway.model.chain.drum_temperature`)."""
        return chain.drum_temperature(self, time_s, **kw)

    def evaluate(self, time_s: ArrayLike, hand_force_N: ArrayLike, direction="downhill", **kw) -> BrakeSeries:
        """The drum chain, steps 1–8, for every element of the broadcast inputs (:func:`rollaway.model.chain.evaluate`,
        keywords ``mu_drum``, ``gap_m``, ``initial_temp_C``, ``ambient_C``, ``heat_transfer_W_m2K``,
        ``test_index``, ``values``, ``drum_temp_C``, ``test_ids``)."""
        return chain.evaluate(self, time_s, hand_force_N, direction, **kw)

    def unenergised_force(self, u6, dT, lining_modulus_Pa=None, gap_m=None):
        """Clamp force before self-energising, eq. (16a/b) [N] (:func:`rollaway.model.chain.unenergised_force`)."""
        return chain.unenergised_force(self, u6, dT, lining_modulus_Pa, gap_m)


def _all_neutral(effect: Effect, v: dict) -> bool:
    """Neutral test that tolerates array values (uncertainty draws): neutral only if every element is."""
    if all(type(x) is float for x in v.values()):      # the fits' case, without numpy's per-value overhead
        return bool(effect.is_neutral(v))
    if all(np.ndim(x) == 0 for x in v.values()):
        return bool(effect.is_neutral({k: float(x) for k, x in v.items()}))
    return False


def load_model(source: str | Path | None = None) -> DrumModel:
    """A named set (``"paper"``), a parameter file or a model file as a :class:`DrumModel` (= ``DrumModel(source)``)."""
    return DrumModel(source)


def as_model(model_or_params) -> DrumModel:
    """A :class:`DrumModel` from a model, a parameter set, a set name or a file (None: the paper set)."""
    if isinstance(model_or_params, DrumModel):
        return model_or_params
    return DrumModel(model_or_params)


__all__ = ["BASELINE_BOUNDS", "BASELINE_FREE", "BASELINE_UNITS", "BrakeSeries", "Covariance", "DrumModel",
           "as_model", "direction_to_sign", "load_model"]
