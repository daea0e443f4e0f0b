"""The fixed interface every physical effect implements (the plugin contract).

An effect is a small class with documented physics, the signature it leaves in the
residuals of the paper's 1D model, parameters with units, bounds and a neutral value,
and a reference.  It changes the model only through *hooks*, each called at one
depth of the model chain (docs/model.md, "Model chain" items 1–7)::

    drum temperature T_d(t)        hook: drum_temperature   (cooling law; the measured channel)
    lining temperature T_l(t)      hook: lining_temperature (what the lining/shoe feels; default T_d)
    lining displacement u_6        hook: displacement       (eq. 24)
    lining modulus E_l             hook: lining_modulus     (eq. 16 material value)
    installation gap l_g           hook: gap                (eq. 16b)
    clamp force F_l0               hook: clamp_force        (eq. 16a/b, before self-energising)
    friction coefficient μ         hook: friction           (eqs. 17b–21)
    measured torque                hook: torque             (the transducer: zero offset, gain)

Each hook receives the :class:`ModelState` (all samples of all tests, already computed
upstream quantities) and ``v``, a dict of this effect's parameter values, and returns
the (possibly) modified quantity.  The default hooks return the input unchanged.
The model skips an effect whose parameters are all at their neutral values, so the
neutral model is bit-identical to the baseline (:func:`rollaway.model.brake.drum_brake`).

Hooks see the test of every sample: ``state.test_index`` (position in ``state.test_ids``).
A parameter declared with ``per_test=True`` takes one value per test; the hook then gets
``v[name]`` as a per-sample array (each sample carries its own test's value), and the fit
estimates one value per test (e.g. a torque transducer's zero, re-set before each test).

Writing your own effect (plugin)::

    # my_effect.py, used as:  rollaway fit DATA.csv --effect-file my_effect.py --effect humidity
    from rollaway.effects.base import Effect, EffectParameter

    class Humidity(Effect):
        name = "humidity"
        summary = "moisture raises the lining friction while the drum is still cold"
        physics = "μ = μ_d·(1 + a·exp(−(T_l − T_amb)/30 K))"
        signature = "torque residual grows at the cold end of every test, both directions"
        reference = "your bench notes"
        parameters = (EffectParameter("a", "–", neutral=0.0, lower=0.0, upper=1.0, initial=0.05,
                                      description="relative friction gain when cold"),)

        def friction(self, state, mu, v):
            return mu * (1 + v["a"] * np.exp(-(state.lining_temp_C - state.ambient_C) / 30.0))

A module passed with ``--effect-file`` may define any number of ``Effect`` subclasses
(each with a unique ``name``); an installed package may expose them under the entry-point
group ``rollaway.effects`` (``name = "package.module:ClassName"``).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from rollaway.errors import UserError


@dataclass(frozen=True)
class EffectParameter:
    """One parameter of an effect: unit, neutral value (no effect), bounds and the fit's start."""

    name: str
    unit: str
    neutral: float
    lower: float
    upper: float
    initial: float          # starting point of a fit (off the neutral bound)
    description: str = ""
    typical: float | None = None   # a clearly visible but realistic value (synth default)
    per_test: bool = False         # one value per test (hooks get a per-sample array)
    held: bool = False             # never fitted (the data cannot see it): fits keep its neutral value, the
                                   # calibrated model takes `initial`, and the predictive covariance gives it the
                                   # spread prior_sd about that, which the bands draw
    prior_sd: float | None = None  # the assumed spread of a held parameter (drawn within its bounds)

    def __post_init__(self):
        if not (self.lower <= self.neutral <= self.upper and self.lower <= self.initial <= self.upper):
            raise ValueError(f"parameter '{self.name}': neutral and initial must lie in [lower, upper]")


@dataclass
class ModelState:
    """All samples of all tests, flattened; filled stage by stage by the model."""

    params: "BrakeParameters"     # rollaway.model.parameters.BrakeParameters (not imported: effects sit below model)
    time_s: np.ndarray
    hand_force_N: np.ndarray
    sign: np.ndarray               # +1 facing downhill, −1 uphill (eqs. 18/19)
    initial_temp_C: np.ndarray     # T_0 of the sample's test
    ambient_C: np.ndarray
    heat_transfer_W_m2K: float
    mu_drum: float
    drum_temp_C: np.ndarray | None = None
    lining_temp_C: np.ndarray | None = None
    test_index: np.ndarray | None = None   # index of each sample's test (bench data), None on the road
    test_ids: list | None = None           # test id of each index (bench data)
    extra: dict = field(default_factory=dict)

    @property
    def cooling_time_constant_s(self) -> float:
        """Convective τ = ρ c_p V / (h A) with the state's (fitted) h [s]."""
        p = self.params
        return (p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3
                / (self.heat_transfer_W_m2K * p.cooled_area_m2))

    @property
    def delta_drum_K(self) -> np.ndarray:
        return self.drum_temp_C - self.initial_temp_C

    @property
    def delta_lining_K(self) -> np.ndarray:
        return self.lining_temp_C - self.initial_temp_C


class Effect:
    """Base class of a physical effect; subclass it and override the hooks you need."""

    name: ClassVar[str] = ""
    summary: ClassVar[str] = ""
    physics: ClassVar[str] = ""
    signature: ClassVar[str] = ""
    reference: ClassVar[str] = ""
    parameters: ClassVar[tuple[EffectParameter, ...]] = ()
    # covariate of the effect's flexible (shape-free) form drawn by diagnose when the form mismatches:
    # "time_s", "lining_temp_C", "drum_temp_C" or "hand_force_N"; "" = chosen from the hook
    shape_covariate: ClassVar[str] = ""
    # where the effect's physics is an absolute change of its hook's quantity (a displacement lost, the same at
    # every hand force), the unit s of that change [the quantity's unit]: the flexible form is q + s·g(x) instead
    # of q·(1 + g(x)), which would make the change proportional to q; 0 = proportional (the default)
    shape_scale: ClassVar[float] = 0.0
    # the parameter whose neutral value switches the effect off whatever the others are (e.g. a lost
    # fraction, not its time constant); "" = the effect is neutral only when every parameter is
    amplitude: ClassVar[str] = ""
    # True when every hook computes each sample from that sample's inputs and values alone (no test ids, no
    # reductions over samples, no table whose grid depends on other samples), values given per sample
    # included: a fit may then evaluate several parameter sets in one call on stacked copies of the data
    # (same numbers, less per-call overhead).  False (the default) is safe.
    elementwise: ClassVar[bool] = False

    # -- bookkeeping -----------------------------------------------------------------
    @classmethod
    def parameter(cls, name: str) -> EffectParameter:
        for p in cls.parameters:
            if p.name == name:
                return p
        from rollaway.errors import suggest
        raise UserError(f"effect '{cls.name}' has no parameter '{name}'"
                        f"{suggest(name, [p.name for p in cls.parameters])}; its parameters are: "
                        + ", ".join(p.name for p in cls.parameters))

    @classmethod
    def neutral_values(cls) -> dict[str, float]:
        return {p.name: p.neutral for p in cls.parameters}

    @classmethod
    def typical_values(cls) -> dict[str, float]:
        return {p.name: (p.typical if p.typical is not None else p.initial) for p in cls.parameters}

    @classmethod
    def is_neutral(cls, v: dict[str, float]) -> bool:
        """True if the values *v* leave the chain unchanged (the effect can be skipped)."""
        params = [cls.parameter(cls.amplitude)] if cls.amplitude else cls.parameters
        for p in params:
            x = v.get(p.name, p.neutral)
            if not (x == p.neutral if type(x) is float else np.all(np.asarray(x) == p.neutral)):
                return False
        return True

    @classmethod
    def per_test_parameters(cls) -> list[str]:
        return [p.name for p in cls.parameters if p.per_test]

    @classmethod
    def overridden_hooks(cls) -> list[str]:
        """Names of the hooks this effect changes."""
        return [h for h in HOOKS if getattr(cls, h) is not getattr(Effect, h)]

    @classmethod
    def touches_temperature(cls) -> bool:
        """True if the effect changes the measured drum-temperature channel."""
        return cls.drum_temperature is not Effect.drum_temperature

    @classmethod
    def describe(cls) -> str:
        lines = [f"{cls.name}: {cls.summary}", f"  physics:   {cls.physics}",
                 f"  signature: {cls.signature}", f"  reference: {cls.reference}"]
        for p in cls.parameters:
            lines.append(f"  {p.name} [{p.unit}]: neutral {p.neutral:g}, bounds [{p.lower:g}, {p.upper:g}]"
                         f" — {p.description}")
        return "\n".join(lines)

    # -- hooks (default: no change) ------------------------------------------------------
    def drum_temperature(self, state: ModelState, temp_C: np.ndarray, v: dict) -> np.ndarray:
        return temp_C

    def lining_temperature(self, state: ModelState, temp_C: np.ndarray, v: dict) -> np.ndarray:
        return temp_C

    def displacement(self, state: ModelState, u6_m: np.ndarray, v: dict) -> np.ndarray:
        return u6_m

    def lining_modulus(self, state: ModelState, modulus_Pa, v: dict):
        return modulus_Pa

    def gap(self, state: ModelState, gap_m, v: dict):
        return gap_m

    def clamp_force(self, state: ModelState, force_N: np.ndarray, v: dict) -> np.ndarray:
        return force_N

    def friction(self, state: ModelState, mu: np.ndarray, v: dict) -> np.ndarray:
        return mu

    def torque(self, state: ModelState, torque_Nm: np.ndarray, v: dict) -> np.ndarray:
        """The measured torque (the transducer), after eq. (17b)."""
        return torque_Nm


HOOKS = ("drum_temperature", "lining_temperature", "displacement", "lining_modulus", "gap", "clamp_force",
         "friction", "torque")
