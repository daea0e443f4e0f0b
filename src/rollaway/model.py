"""The drum model: ONE chain from hand force to brake torque, with optional physical effects.

:class:`DrumModel` = a parameter set (:class:`~rollaway.parameters.BrakeParameters`) +
effects (:mod:`rollaway.effects`, the catalogue or plugins) + the effects' values, and,
for a model calibrated on bench data, the covariance of the fitted parameters and where
they came from.  Every part of rollaway evaluates the drum through :meth:`DrumModel.evaluate`:
the analytic hold check (:mod:`rollaway.hold`), the MuJoCo brake callback, sweeps, figures
and the fits of :mod:`rollaway.identify`.

Follow ``hand_force_N`` through :meth:`DrumModel.evaluate`:

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

from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from rollaway.covariance import Covariance
from rollaway.effects.base import Effect, ModelState
from rollaway.effects.hooks import call_hook
from rollaway.errors import UserError
from rollaway.parameters import BrakeParameters
from rollaway.drum_parameters import BASELINE_BOUNDS, BASELINE_FREE, BASELINE_UNITS, apply, values_of
from rollaway.physics import cooling, drum

_PARAMETER_NAMES = frozenset(f.name for f in fields(BrakeParameters)) | {"cooling_time_constant_s"}

# Brake parameters a calibration may free, their bounds and units: rollaway.drum_parameters
CHAIN_OVERRIDES = ("u6_slope_m_per_N", "u6_offset_m", "shoe_arm_ratio", "ambient_temp_C")


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


def direction_to_sign(direction) -> np.ndarray:
    """+1 facing downhill (eq. 18), −1 uphill (eq. 19); accepts names or numeric signs."""
    d = np.asarray(direction)
    if d.dtype.kind in "biuf":
        return np.where(d.astype(float) < 0, -1.0, 1.0)
    return drum.direction_sign(direction)


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
            from rollaway.model_file import read_model
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
        self.predictive: dict = dict(predictive or {})    # model error, tested range (rollaway.predictive)
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
        """Every value a calibration may move: the brake parameters (:mod:`rollaway.drum_parameters`) and
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

    # -- the chain ---------------------------------------------------------------------
    def state(self, time_s, hand_force_N, direction="downhill", *, mu_drum=None, initial_temp_C=None,
              ambient_C=None, heat_transfer_W_m2K=None, test_index=None, test_ids=None) -> ModelState:
        """Inputs of the chain broadcast to one shape, as the effect hooks see them."""
        p = self.params
        sign = direction_to_sign(direction)
        mu = p.mu_drum if mu_drum is None else mu_drum
        t0 = p.initial_drum_temp_C if initial_temp_C is None else initial_temp_C
        amb = p.ambient_temp_C if ambient_C is None else ambient_C
        h = p.heat_transfer_W_m2K if heat_transfer_W_m2K is None else heat_transfer_W_m2K
        arrays = [np.asarray(x, float) for x in (time_s, hand_force_N, sign, t0, amb)]
        shape = np.broadcast_shapes(*(a.shape for a in arrays), np.shape(mu), np.shape(h))
        t, f, s, t0b, ambb = (np.broadcast_to(a, shape) for a in arrays)
        tid = None if test_index is None else np.broadcast_to(np.asarray(test_index), shape)
        return ModelState(p, t, f, s, t0b, ambb, h, mu, test_index=tid, test_ids=test_ids)

    def drum_temperature(self, time_s, *, initial_temp_C=None, ambient_C=None, heat_transfer_W_m2K=None,
                         values: dict | None = None, state: ModelState | None = None,
                         base_temp_C: ArrayLike | None = None, **state_kw) -> np.ndarray:
        """Drum temperature over time, eq. (10) plus the effects' ``drum_temperature`` hooks [°C].

        *base_temp_C*: the cooling law's temperature when it was integrated elsewhere (a logged,
        time-varying ambient, :func:`rollaway.physics.cooling.drum_temperature_logged_ambient_C`).
        """
        p = self.params
        t0 = p.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
        amb = p.ambient_temp_C if ambient_C is None else ambient_C
        h = p.heat_transfer_W_m2K if heat_transfer_W_m2K is None else heat_transfer_W_m2K
        tau = cooling.cooling_time_constant_s(p.drum_density_kg_m3, p.drum_specific_heat_J_kgK, p.drum_volume_m3,
                                              h, p.cooled_area_m2)
        temp = cooling.drum_temperature_C(time_s, t0, amb, tau) if base_temp_C is None else base_temp_C
        hooks = [(e, v) for e, v in self.active(values) if e.touches_temperature()]
        if not hooks:
            return temp
        st = state or self.state(time_s, state_kw.pop("hand_force_N", 0.0), state_kw.pop("direction", "downhill"),
                                 initial_temp_C=t0, ambient_C=amb, heat_transfer_W_m2K=h, **state_kw)
        temp = np.broadcast_to(temp, st.time_s.shape)
        for e, v in hooks:
            temp = call_hook(e, "drum_temperature", st, temp, v)
        return temp

    def evaluate(self, time_s: ArrayLike, hand_force_N: ArrayLike, direction="downhill", *,
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
        active = self.active(values)
        if not active:
            return self._baseline(time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
                                  heat_transfer_W_m2K, drum_temp_C, brake)
        return self._with_effects(active, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C,
                                  ambient_C, heat_transfer_W_m2K, test_index, values, drum_temp_C, test_ids, brake)

    def _lever(self, hand_force_N, brake: dict):
        """u_6 from the hand force, eq. (24), and the friction arm l_fr, with calibrated overrides in *brake*."""
        p = self.params
        u6 = drum.lining_displacement_m(hand_force_N, brake.get("u6_slope_m_per_N", p.u6_slope_m_per_N),
                                        brake.get("u6_offset_m", p.u6_offset_m))                  # eq. (24)
        arm = p.shoe_arm_friction_m if "shoe_arm_ratio" not in brake else brake["shoe_arm_ratio"] * p.shoe_arm_normal_m
        return u6, arm

    def _baseline(self, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
                  heat_transfer_W_m2K, drum_temp_C, brake=None) -> BrakeSeries:
        """The paper's chain, Ishak et al. 2018 eqs. (10), (16a/b), (17b), (18)–(21), (24)."""
        p = self.params
        mu = p.mu_drum if mu_drum is None else np.asarray(mu_drum, float)
        t0 = p.initial_drum_temp_C if initial_temp_C is None else np.asarray(initial_temp_C, float)
        temp = (self.drum_temperature(time_s, initial_temp_C=t0, ambient_C=ambient_C,
                                      heat_transfer_W_m2K=heat_transfer_W_m2K)
                if drum_temp_C is None else np.asarray(drum_temp_C, float))
        dT = cooling.temperature_change_K(temp, t0)                                           # ΔT, eq. (16)
        u6, arm_friction_m = self._lever(hand_force_N, brake or {})                          # eq. (24)
        f0 = self.unenergised_force(u6, dT, p.lining_modulus_Pa, p.gap_m if gap_m is None else np.asarray(gap_m, float))
        factor = drum.self_energising_factor(mu, direction_to_sign(direction), p.shoe_arm_normal_m,
                                             arm_friction_m)                               # eqs. (18)–(21)
        f_l = drum.normal_force_N(f0, factor)
        torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)                             # eq. (17b)
        shape = np.broadcast_shapes(np.shape(time_s), np.shape(temp), np.shape(f_l))
        b = lambda a: np.broadcast_to(np.asarray(a, float), shape)  # noqa: E731
        return BrakeSeries(time_s=b(time_s), drum_temp_C=b(temp), normal_force_N=b(f_l), torque_Nm=b(torque),
                           self_locked=np.broadcast_to(np.isinf(factor), shape), lining_temp_C=b(temp))

    def unenergised_force(self, u6, dT, lining_modulus_Pa=None, gap_m=None):
        """Clamp force before self-energising, eq. (16a) (gap 0) or (16b), with the set's material values [N]."""
        p = self.params
        lining_modulus_Pa = p.lining_modulus_Pa if lining_modulus_Pa is None else lining_modulus_Pa
        gap_m = p.gap_m if gap_m is None else gap_m
        return drum.normal_force_unenergised_N(
            u6, dT, drum_area_m2=p.drum_area_m2, drum_modulus_Pa=p.drum_modulus_Pa, lining_area_m2=p.lining_area_m2,
            lining_modulus_Pa=lining_modulus_Pa, drum_expansion_per_K=p.drum_expansion_per_K,
            lining_expansion_per_K=p.lining_expansion_per_K, drum_thickness_m=p.drum_thickness_m,
            lining_thickness_m=p.lining_thickness_m, gap_m=gap_m)

    def _with_effects(self, active, time_s, hand_force_N, direction, mu_drum, gap_m, initial_temp_C, ambient_C,
                      heat_transfer_W_m2K, test_index, values, drum_temp_C, test_ids=None, brake=None) -> BrakeSeries:
        p = self.params
        st = self.state(time_s, hand_force_N, direction, mu_drum=mu_drum, initial_temp_C=initial_temp_C,
                        ambient_C=ambient_C, heat_transfer_W_m2K=heat_transfer_W_m2K, test_index=test_index,
                        test_ids=test_ids)
        shape = st.time_s.shape
        for e, v in active:                       # effect values may be arrays (uncertainty draws)
            shape = np.broadcast_shapes(shape, *(np.shape(x) for x in v.values()))
        if shape != st.time_s.shape:
            st = self.state(*(np.broadcast_to(a, shape) for a in (st.time_s, st.hand_force_N, st.sign)),
                            mu_drum=st.mu_drum, initial_temp_C=np.broadcast_to(st.initial_temp_C, shape),
                            ambient_C=np.broadcast_to(st.ambient_C, shape),
                            heat_transfer_W_m2K=st.heat_transfer_W_m2K,
                            test_index=None if st.test_index is None else np.broadcast_to(st.test_index, shape),
                            test_ids=test_ids)
        temp = (self.drum_temperature(st.time_s, initial_temp_C=st.initial_temp_C, ambient_C=st.ambient_C,
                                      heat_transfer_W_m2K=st.heat_transfer_W_m2K, values=values, state=st)
                if drum_temp_C is None else drum_temp_C)
        st.drum_temp_C = np.broadcast_to(np.asarray(temp, float), shape)
        lining = st.drum_temp_C
        for e, v in active:                                                     # step 2
            lining = call_hook(e, "lining_temperature", st, lining, v)
        st.lining_temp_C = lining
        dT = cooling.temperature_change_K(st.drum_temp_C, st.initial_temp_C)   # ΔT of the drum, eq. (16)
        u6, arm_friction_m = self._lever(st.hand_force_N, brake or {})         # eq. (24)
        modulus = p.lining_modulus_Pa
        gap = p.gap_m if gap_m is None else np.asarray(gap_m, float)
        for e, v in active:                                                     # steps 3–4
            u6 = call_hook(e, "displacement", st, u6, v)
            modulus = call_hook(e, "lining_modulus", st, modulus, v, scalar_ok=True)
            gap = call_hook(e, "gap", st, gap, v, scalar_ok=True)
        f0 = self.unenergised_force(u6, dT, modulus, gap)                            # step 5, eq. (16a/b)
        k_d = p.drum_area_m2 * p.drum_modulus_Pa
        k_l = p.lining_area_m2 * np.asarray(modulus)
        l_eff = p.lining_thickness_m + np.asarray(gap)
        den = k_l * p.drum_thickness_m + k_d * l_eff
        st.extra["series_stiffness_N_per_m"] = k_d * k_l / den
        if lining is not st.drum_temp_C:   # the lining's own thermal strain α_l·ΔT_l replaces α_l·ΔT_d (eq. 16)
            f0 = f0 + k_d * k_l * p.lining_expansion_per_K * l_eff * (lining - st.drum_temp_C) / den
        for e, v in active:
            f0 = call_hook(e, "clamp_force", st, f0, v)
        mu = np.broadcast_to(np.asarray(st.mu_drum, float), shape)
        for e, v in active:                                                     # step 6
            mu = call_hook(e, "friction", st, mu, v)
        factor = drum.self_energising_factor(mu, st.sign, p.shoe_arm_normal_m, arm_friction_m)  # step 7
        f_l = drum.normal_force_N(f0, factor)
        torque = drum.brake_torque_Nm(mu, f_l, p.drum_radius_m)                 # step 8, eq. (17b)
        for e, v in active:
            torque = call_hook(e, "torque", st, torque, v)
        b = lambda a: np.broadcast_to(np.asarray(a, float), shape)  # noqa: E731
        return BrakeSeries(time_s=b(st.time_s), drum_temp_C=b(st.drum_temp_C), normal_force_N=b(f_l),
                           torque_Nm=b(torque), self_locked=np.broadcast_to(np.isinf(factor), shape),
                           lining_temp_C=b(lining))


def _all_neutral(effect: Effect, v: dict) -> bool:
    """Neutral test that tolerates array values (uncertainty draws): neutral only if every element is."""
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
