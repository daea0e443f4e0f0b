"""Named parameter sets and their validation.

The set ``paper`` is Table 1 of Ishak et al. (2018) plus the values the paper does
not give, each marked **assumed** with the reason (see ``docs/model.md``, section "Parameters").
Users load their own set from TOML::

    extends = "paper"        # optional: start from a named set, override some keys
    mu_drum = 0.35
    heat_transfer_W_m2K = 30

Without ``extends`` every key must be given.  Unknown keys, missing keys and
non-numeric or out-of-range values are :class:`~rollaway.errors.UserError` naming
the file and the key.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, fields
from pathlib import Path

from rollaway.errors import UserError, read_toml, suggest

PAPER = "Ishak et al. 2018, Table 1"
EQ24 = "Ishak et al. 2018, eq. (24) (fit to bench data)"
ASSUMED = "assumed (docs/model.md, Parameters)"


@dataclass(frozen=True)
class ParamSpec:
    name: str
    symbol: str
    unit: str
    value: float
    source: str
    description: str
    lower: float = -math.inf     # inclusive physical bounds used for validation
    upper: float = math.inf
    assumed: bool = False


# Bounds are the physical range a value may take (inclusive); they are wide on purpose (any
# passenger car to a heavy truck, any road surface, any metal drum) and only reject nonsense.
# Where a bound is not a law of physics it is an engineering judgement, "assumed" like the values.
SPECS: tuple[ParamSpec, ...] = (
    ParamSpec("ambient_temp_C", "T_amb", "°C", 27.0, PAPER, "ambient temperature", -60, 80),
    ParamSpec("vehicle_mass_kg", "m", "kg", 1250.0, PAPER, "vehicle mass (kerb, wheels included)", 100, 40000),
    ParamSpec("occupant_mass_kg", "m_d", "kg", 70.0, PAPER, "mass of one occupant", 0, 300),
    ParamSpec("drum_volume_m3", "V", "m³", 7.7e-4, PAPER, "drum volume", 1e-6, 0.1),
    ParamSpec("drum_radius_m", "r_d", "m", 0.09, PAPER, "drum radius", 0.01, 1.0),
    ParamSpec("drum_specific_heat_J_kgK", "c_p", "J/(kg K)", 586.0, PAPER, "drum specific heat", 100, 5000),
    ParamSpec("drum_density_kg_m3", "ρ", "kg/m³", 7100.0, PAPER, "drum density", 500, 25000),
    ParamSpec("wheel_radius_m", "R_wheel", "m", 0.3, PAPER, "wheel (tyre) rolling radius", 0.05, 2.0),
    ParamSpec("drum_modulus_Pa", "E_d", "Pa", 1.1e11, PAPER, "drum Young's modulus", 1e8, 1e12),
    ParamSpec("lining_modulus_Pa", "E_l", "Pa", 2.1e8, PAPER, "lining Young's modulus", 1e5, 1e11),
    ParamSpec("drum_area_m2", "A_d", "m²", 2.2e-3, PAPER, "drum area in the force path", 1e-6, 1.0),
    ParamSpec("lining_area_m2", "A_l", "m²", 4.8e-3, PAPER, "lining area in the force path", 1e-6, 1.0),
    ParamSpec("drum_expansion_per_K", "α_d", "1/K", 1.1e-5, PAPER, "drum thermal expansion coefficient", 0, 1e-3),
    ParamSpec("lining_expansion_per_K", "α_l", "1/K", 1.2e-5, PAPER, "lining thermal expansion coefficient", 0, 1e-3),
    ParamSpec("drum_thickness_m", "l_od", "m", 0.008, PAPER, "drum thickness", 1e-4, 0.1),
    ParamSpec("lining_thickness_m", "l_ol", "m", 0.004, PAPER, "lining thickness", 1e-4, 0.1),
    ParamSpec("mu_drum", "μ_d", "–", 0.4, ASSUMED + ": paper gives the range 0.3–0.6",
              "shoe/drum friction coefficient", 0, 2, assumed=True),
    ParamSpec("gap_m", "l_g", "m", 0.0, ASSUMED + ": Table 1 lists 1 mm; 0 selects eq. (16a)",
              "installation gap lining/drum (> 0 selects eq. 16b)", 0, 0.05, assumed=True),
    ParamSpec("heat_transfer_W_m2K", "h", "W/(m² K)", 40.0, ASSUMED + ": not in Table 1; τ ≈ 1001 s",
              "convective heat-transfer coefficient", 0.01, 1e4, assumed=True),
    ParamSpec("cooled_area_m2", "A_conv", "m²", 0.08, ASSUMED + ": not in Table 1",
              "cooled surface of the drum", 1e-4, 10, assumed=True),
    ParamSpec("shoe_arm_normal_m", "l_f", "m", 0.07, ASSUMED + ": Fig. 6, not in Table 1",
              "shoe pivot arm of the normal force", 1e-3, 1.0, assumed=True),
    ParamSpec("shoe_arm_friction_m", "l_fr", "m", 0.06, ASSUMED + ": Fig. 6, the paper's second 'l_g'",
              "shoe pivot arm of the friction force", 0, 1.0, assumed=True),
    ParamSpec("initial_drum_temp_C", "T_0", "°C", 200.0, "Ishak et al. 2018, bench tests",
              "drum temperature when the lever is applied", -60, 1000),
    ParamSpec("u6_slope_m_per_N", "", "m/N", 3.89e-7, EQ24, "slope of u_6 against hand force", 0, 1e-4),
    ParamSpec("u6_offset_m", "", "m", -1.5e-5, EQ24, "offset of u_6", -0.01, 0.01),
    ParamSpec("gravity_m_s2", "g", "m/s²", 9.81, ASSUMED + ": standard value", "gravitational acceleration",
              0.5, 30, assumed=True),
    ParamSpec("wheelbase_m", "L", "m", 2.6, ASSUMED + ": vehicle geometry", "wheelbase", 0.5, 10, assumed=True),
    ParamSpec("track_m", "", "m", 1.5, ASSUMED + ": vehicle geometry", "track width", 0.5, 5, assumed=True),
    ParamSpec("cg_behind_front_m", "a", "m", 1.1, ASSUMED + ": vehicle geometry",
              "centre of gravity behind the front axle (< wheelbase)", 0, 10, assumed=True),
    ParamSpec("cg_height_m", "h_cg", "m", 0.55, ASSUMED + ": vehicle geometry", "centre of gravity height",
              0.05, 5, assumed=True),
    ParamSpec("tyre_road_mu", "μ_r", "–", 0.8, ASSUMED + ": dry asphalt", "tyre–road friction coefficient",
              0, 3, assumed=True),
    ParamSpec("front_seat_behind_front_m", "", "m", 1.3, ASSUMED + ": vehicle geometry",
              "front-row seats behind the front axle", 0, 10, assumed=True),
    ParamSpec("rear_seat_behind_front_m", "", "m", 2.2, ASSUMED + ": vehicle geometry",
              "rear-row seats behind the front axle", 0, 10, assumed=True),
    ParamSpec("seat_height_m", "", "m", 0.5, ASSUMED + ": vehicle geometry", "occupant CG height", 0, 5,
              assumed=True),
)

SPEC_BY_NAME = {s.name: s for s in SPECS}


@dataclass(frozen=True)
class BrakeParameters:
    """One complete parameter set (SI units, temperatures in °C).  Build with :func:`load_parameters`."""

    ambient_temp_C: float
    vehicle_mass_kg: float
    occupant_mass_kg: float
    drum_volume_m3: float
    drum_radius_m: float
    drum_specific_heat_J_kgK: float
    drum_density_kg_m3: float
    wheel_radius_m: float
    drum_modulus_Pa: float
    lining_modulus_Pa: float
    drum_area_m2: float
    lining_area_m2: float
    drum_expansion_per_K: float
    lining_expansion_per_K: float
    drum_thickness_m: float
    lining_thickness_m: float
    mu_drum: float
    gap_m: float
    heat_transfer_W_m2K: float
    cooled_area_m2: float
    shoe_arm_normal_m: float
    shoe_arm_friction_m: float
    initial_drum_temp_C: float
    u6_slope_m_per_N: float
    u6_offset_m: float
    gravity_m_s2: float
    wheelbase_m: float
    track_m: float
    cg_behind_front_m: float
    cg_height_m: float
    tyre_road_mu: float
    front_seat_behind_front_m: float
    rear_seat_behind_front_m: float
    seat_height_m: float
    name: str = "custom"

    def replace(self, **changes) -> "BrakeParameters":
        """A copy with some values changed, each validated like a file entry."""
        for key, value in changes.items():
            if key != "name":
                changes[key] = _validate_value(key, value, "replace()")
        out = dataclasses.replace(self, **changes)
        check_derived(out.as_dict(), "replace()")
        return out

    def with_overrides(self, overrides) -> "BrakeParameters":
        """A copy with ``(key, value, where)`` overrides applied; ``value=None`` keeps the set's value.

        *where* names the input (a CLI flag, a file key) in the error message of a bad value.
        """
        overrides = [(k, v, where) for k, v, where in overrides if v is not None]
        changes = {k: _validate_value(k, v, where) for k, v, where in overrides}
        if not changes:
            return self
        out = dataclasses.replace(self, **changes)
        check_derived(out.as_dict(), ", ".join(dict.fromkeys(where for _, _, where in overrides)))
        return out

    def as_dict(self) -> dict[str, float]:
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "name"}

    @property
    def cooling_time_constant_s(self) -> float:
        from rollaway.physics.cooling import cooling_time_constant_s
        return float(cooling_time_constant_s(self.drum_density_kg_m3, self.drum_specific_heat_J_kgK,
                                             self.drum_volume_m3, self.heat_transfer_W_m2K,
                                             self.cooled_area_m2))


def _validate_value(key: str, value, where: str) -> float:
    if key not in SPEC_BY_NAME:
        raise UserError(f"{where}: unknown parameter '{key}'{suggest(key, SPEC_BY_NAME)}; "
                        f"run 'rollaway params' to list the valid names")
    spec = SPEC_BY_NAME[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        unit = "without unit" if spec.unit in ("–", "-", "") else f"in {spec.unit}"
        raise UserError(f"{where}: parameter '{key}' must be a number ({unit}), got {value!r}; "
                        f"write a plain number without quotes (not \"{value}\")")
    v = float(value)
    if not math.isfinite(v) or not (spec.lower <= v <= spec.upper):
        raise UserError(f"{where}: parameter '{key}' = {value!r} is outside [{spec.lower:g}, {spec.upper:g}] "
                        f"{spec.unit}; give a physical value")
    return v


def check_derived(values: dict[str, float], where: str) -> None:
    """Quantities derived from several parameters must be physical too (UserError naming the keys).

    * cooling time constant τ = ρ c_p V / (h A) (eq. 10) finite and positive;
    * the centre of gravity between the axles (``cg_behind_front_m`` < ``wheelbase_m``), or the
      static axle loads of the slope balance turn negative.
    """
    tau = (values["drum_density_kg_m3"] * values["drum_specific_heat_J_kgK"] * values["drum_volume_m3"]
           / (values["heat_transfer_W_m2K"] * values["cooled_area_m2"]))
    if not (math.isfinite(tau) and tau > 0):
        raise UserError(f"{where}: the cooling time constant τ = ρ·c_p·V/(h·A) from 'drum_density_kg_m3', "
                        f"'drum_specific_heat_J_kgK', 'drum_volume_m3', 'heat_transfer_W_m2K' and "
                        f"'cooled_area_m2' is {tau:g} s; it must be finite and > 0")
    if not values["cg_behind_front_m"] < values["wheelbase_m"]:
        raise UserError(f"{where}: 'cg_behind_front_m' = {values['cg_behind_front_m']:g} m is not less than "
                        f"'wheelbase_m' = {values['wheelbase_m']:g} m; the centre of gravity must lie between "
                        f"the axles")


def parameter_ranges() -> list[tuple[str, str, float, float]]:
    """(name, unit, lower, upper) of every parameter: the accepted physical range."""
    return [(s.name, s.unit, s.lower, s.upper) for s in SPECS]


PARAMETER_SETS: dict[str, dict[str, float]] = {
    "paper": {s.name: s.value for s in SPECS},
}


def paper() -> BrakeParameters:
    """The ``paper`` set: Ishak et al. (2018) Table 1 plus the assumed values of docs/model.md."""
    return BrakeParameters(**PARAMETER_SETS["paper"], name="paper")


def load_parameters(source: str | Path | None = None, referenced_by: str = "") -> BrakeParameters:
    """Return a named set (``"paper"``) or a set read from a TOML file; ``None`` means ``paper``.

    *referenced_by* ("scenario.toml, key 'params'") prefixes every error, so a mistake inside
    the parameter file also names the file and key that pointed to it.
    """
    if not referenced_by:
        return _load_parameters(source)
    try:
        return _load_parameters(source)
    except UserError as exc:
        raise UserError(f"{referenced_by}: {exc}") from None


def _load_parameters(source) -> BrakeParameters:
    if source is None:
        return paper()
    text = str(source)
    if text in PARAMETER_SETS:
        return BrakeParameters(**PARAMETER_SETS[text], name=text)
    path = Path(text)
    if not path.suffix == ".toml" and not path.exists():
        raise UserError(f"unknown parameter set '{text}'{suggest(text, PARAMETER_SETS)}; give a named set "
                        f"({', '.join(PARAMETER_SETS)}) or the path of a .toml file")
    data = read_toml(path, "parameter file", "see 'rollaway params' for the keys")
    return parameters_from_mapping(data, where=str(path))


def parameters_from_mapping(data: dict, where: str = "parameters") -> BrakeParameters:
    """Validate a mapping (already parsed TOML) into a :class:`BrakeParameters`."""
    data = dict(data)
    base_name = data.pop("extends", None)
    if base_name is not None:
        if not isinstance(base_name, str):
            raise UserError(f"{where}: key 'extends' must be a quoted set name, e.g. extends = \"paper\"; "
                            f"got {base_name!r}")
        if base_name not in PARAMETER_SETS:
            raise UserError(f"{where}: key 'extends' = {base_name!r} names no parameter set"
                            f"{suggest(str(base_name), PARAMETER_SETS)}; use one of: {', '.join(PARAMETER_SETS)}")
        values = dict(PARAMETER_SETS[base_name])
    else:
        values = {}
    for key, value in data.items():
        if isinstance(value, dict):
            raise UserError(f"{where}: key '{key}' is a table; parameters are top-level 'name = value' lines "
                            f"with a number")
        values[key] = _validate_value(key, value, where)
    missing = [s.name for s in SPECS if s.name not in values]
    if missing:
        raise UserError(f"{where}: missing parameter '{missing[0]}'"
                        + (f" (and {len(missing) - 1} more)" if len(missing) > 1 else "")
                        + "; add it, or start the file with extends = \"paper\"")
    check_derived(values, where)
    name = Path(where).stem if where.endswith(".toml") else "custom"
    return BrakeParameters(**values, name=name)
