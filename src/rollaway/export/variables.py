"""The FMU's variables: one list that both the C source and ``modelDescription.xml`` are written from.

Four parameters a tool may set before initialization (``hand_force_N``, ``initial_drum_temp_C``,
``ambient_temp_C``, ``facing_uphill``), the outputs of one drum, and the model's values as read-only
constants (the chain's brake parameters and every effect parameter), each with its unit, description
and source.  Value references: 1–9 parameters, 10–19 outputs, 100+ brake values, 200+ effect values.
"""
from __future__ import annotations

from dataclasses import dataclass

from rollaway.hold.closed_form import MAX_HAND_FORCE_N
from rollaway.model.parameters import SPEC_BY_NAME

# The brake parameters the chain reads (rollaway.model.chain); the vehicle's are not part of the drum.
CHAIN_PARAMETERS = (
    "drum_density_kg_m3", "drum_specific_heat_J_kgK", "drum_volume_m3", "heat_transfer_W_m2K", "cooled_area_m2",
    "u6_slope_m_per_N", "u6_offset_m", "drum_area_m2", "drum_modulus_Pa", "lining_area_m2", "lining_modulus_Pa",
    "drum_expansion_per_K", "lining_expansion_per_K", "drum_thickness_m", "lining_thickness_m", "gap_m",
    "mu_drum", "shoe_arm_normal_m", "shoe_arm_friction_m", "drum_radius_m")

# rollaway's unit text → FMI 2.0 unit name and its SI base-unit exponents (FMI 2.0 spec, section 2.2.2)
UNITS = {
    "N": ("N", {"kg": 1, "m": 1, "s": -2}), "N·m": ("N.m", {"kg": 1, "m": 2, "s": -2}),
    "°C": ("degC", {"K": 1, "offset": 273.15}), "K": ("K", {"K": 1}), "s": ("s", {"s": 1}), "m": ("m", {"m": 1}),
    "m²": ("m2", {"m": 2}), "m³": ("m3", {"m": 3}), "Pa": ("Pa", {"kg": 1, "m": -1, "s": -2}),
    "kg/m³": ("kg/m3", {"kg": 1, "m": -3}), "J/(kg K)": ("J/(kg.K)", {"m": 2, "s": -2, "K": -1}),
    "W/(m² K)": ("W/(m2.K)", {"kg": 1, "s": -3, "K": -1}), "1/K": ("1/K", {"K": -1}),
    "m/N": ("m/N", {"kg": -1, "s": 2}), "–": ("1", {}), "-": ("1", {}), "": ("1", {}),
}


@dataclass(frozen=True)
class Variable:
    """One scalar variable of the FMU."""

    name: str                 # also the C name of its value (a parameter, output or constant)
    vr: int                   # value reference
    kind: str                 # "Real" or "Boolean"
    causality: str            # "parameter", "output" or "local" (the read-only constants)
    variability: str          # "fixed", "continuous" or "constant"
    unit: str                 # FMI unit name ("" for a Boolean)
    description: str
    start: float | bool | None = None
    min: float | None = None
    max: float | None = None

    @property
    def c_name(self) -> str:
        return self.name.replace(".", "_")


def fmi_unit(unit: str) -> str:
    return UNITS[unit][0] if unit in UNITS else "1"


def _source(model, name: str, value: float) -> str:
    """Where a brake parameter's value came from: the calibration's words, the model file, or the paper set."""
    spec = SPEC_BY_NAME[name]
    calibration = getattr(model, "calibration", {}) or {}
    if calibration.get(name):
        return f"calibration: {calibration[name]}"
    if name == "shoe_arm_friction_m" and calibration.get("shoe_arm_ratio"):
        return f"calibration of the arm ratio l_fr/l_f (shoe_arm_ratio): {calibration['shoe_arm_ratio']}"
    if value != spec.value:
        return f"the model file (paper set: {spec.value:g} {spec.unit}, {spec.source})"
    return spec.source


def parameters(model) -> list[Variable]:
    """The settable parameters, started at the model's own values (400 N: FMVSS 135 / UN R13-H)."""
    p = model.params
    temp = SPEC_BY_NAME["initial_drum_temp_C"]
    amb = SPEC_BY_NAME["ambient_temp_C"]
    return [
        Variable("hand_force_N", 1, "Real", "parameter", "fixed", "N", "force on the hand lever (eq. 24)", 400.0,
                 0.0, MAX_HAND_FORCE_N),
        Variable("initial_drum_temp_C", 2, "Real", "parameter", "fixed", "degC",
                 "drum temperature T_0 when the lever is applied (eq. 10)", p.initial_drum_temp_C, temp.lower,
                 temp.upper),
        Variable("ambient_temp_C", 3, "Real", "parameter", "fixed", "degC",
                 "ambient temperature T_amb the drum cools towards (eq. 10); start: the model's, "
                 + _source(model, "ambient_temp_C", p.ambient_temp_C), p.ambient_temp_C, amb.lower, amb.upper),
        Variable("facing_uphill", 4, "Boolean", "parameter", "fixed", "",
                 "true: the car faces uphill (eq. 19), false: downhill (eq. 18)", False),
    ]


OUTPUTS = (
    Variable("torque_Nm", 10, "Real", "output", "continuous", "N.m",
             "brake torque of one rear drum, T = mu*F_l*r_d (eq. 17b) plus the effects' torque hooks"),
    Variable("drum_temp_C", 11, "Real", "output", "continuous", "degC",
             "drum temperature (eq. 10 plus the effects' drum-temperature hooks)"),
    Variable("clamp_force_N", 12, "Real", "output", "continuous", "N",
             "normal force F_l of the lining on the drum after self-energising (eqs. 16, 18-21; "
             "normal_force_N of 'rollaway brake')"),
    Variable("lining_temp_C", 13, "Real", "output", "continuous", "degC",
             "lining temperature the shoe feels (the drum's unless an effect lags it)"),
)


def constants(model) -> list[Variable]:
    """The model's values, read-only: the chain's brake parameters (100+) and the effects' (200+)."""
    p = model.params
    out = []
    for k, name in enumerate(CHAIN_PARAMETERS):
        spec = SPEC_BY_NAME[name]
        value = float(getattr(p, name))
        source = _source(model, name, value)
        out.append(Variable(name, 100 + k, "Real", "local", "constant", fmi_unit(spec.unit),
                            f"{spec.symbol + ': ' if spec.symbol else ''}{spec.description}; source: {source}",
                            value))
    k = 0
    for e in model.effects:
        on = any(a is e for a, _ in model.active())
        for par in e.parameters:
            value = float(model.values[f"{e.name}.{par.name}"])
            state = "" if on else " (neutral: the effect is off)"
            out.append(Variable(f"{e.name}.{par.name}", 200 + k, "Real", "local", "constant", fmi_unit(par.unit),
                                f"{par.description}{state}; effect {e.name}: {e.reference}", value))
            k += 1
    return out


def all_variables(model) -> list[Variable]:
    return [*parameters(model), *OUTPUTS, *constants(model)]


__all__ = ["CHAIN_PARAMETERS", "OUTPUTS", "UNITS", "Variable", "all_variables", "constants", "fmi_unit",
           "parameters"]
