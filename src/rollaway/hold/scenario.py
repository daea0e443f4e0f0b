"""Scenarios: one parked car, one grade, one brake application, as a validated TOML file.

Example (``scenarios/fmvss135-uphill.toml``)::

    name = "fmvss135-uphill"
    description = "FMVSS 135 S7.12: 400 N hand force, 20 % grade, facing uphill, laden, 5 min"
    grade_pct = 20
    direction = "uphill"
    occupants = 5
    hand_force_N = 400
    duration_s = 300
    initial_drum_temp_C = 200     # optional; default: the parameter set's T_0
    mu_drum = 0.4                 # optional; default: the parameter set's μ_d
    tyre_road_mu = 0.8            # optional; default: the parameter set's μ_r
    params = "paper"              # optional; a set name, a parameter file or a model file (relative to this file)
    regulation = "fmvss135"       # optional tag: the preset this scenario implements

    [parameters]                  # optional: override any parameter of the set
    heat_transfer_W_m2K = 35

Unknown keys, wrong types and out-of-range values are :class:`UserError` naming the
file and the key.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path

from rollaway.errors import UserError, check_choice, read_toml, suggest
from rollaway.hold import MAX_HAND_FORCE_N, MAX_OCCUPANTS, invalid_grade, invalid_hand_force
from rollaway.model.drum_model import DrumModel
from rollaway.model.parameters import BrakeParameters
from rollaway.physics.drum import DIRECTIONS
from rollaway.hold.regulations import PRESETS


@dataclass(frozen=True)
class Scenario:
    name: str
    grade_pct: float
    direction: str
    occupants: int
    hand_force_N: float
    duration_s: float
    params: BrakeParameters = field(repr=False)
    description: str = ""
    regulation: str | None = None
    source: str | None = None          # file it was read from
    model: DrumModel | None = field(default=None, repr=False, compare=False)   # the drum model (params + effects)

    def __post_init__(self):
        if self.model is None:
            object.__setattr__(self, "model", DrumModel(self.params))
        elif self.model.params is not self.params:      # parameters changed: same effects, new set
            object.__setattr__(self, "model", self.model.with_params(self.params))

    @property
    def mu_drum(self) -> float:
        return self.params.mu_drum

    @property
    def initial_drum_temp_C(self) -> float:
        return self.params.initial_drum_temp_C

    @property
    def tyre_road_mu(self) -> float:
        return self.params.tyre_road_mu

    def replace(self, **changes) -> "Scenario":
        """A copy with scenario fields and/or parameters changed (parameter names go to ``params``)."""
        own = {f.name for f in dataclasses.fields(self)}
        param_changes = {k: v for k, v in changes.items() if k not in own}
        scen_changes = {k: v for k, v in changes.items() if k in own}
        alias = {"initial_drum_temp_C": "initial_drum_temp_C"}
        p = self.params.replace(**{alias.get(k, k): v for k, v in param_changes.items()}) if param_changes \
            else self.params
        out = dataclasses.replace(self, params=p, **scen_changes)
        _validate(out, self.source or "scenario")
        return out


MAX_DURATION_S = 7 * 86400.0   # a week of parking: far beyond the cooling (τ ≈ 1000 s)

# key -> (type, required)
_KEYS = {
    "name": (str, True), "description": (str, False), "grade_pct": (float, True), "direction": (str, True),
    "occupants": (int, True), "hand_force_N": (float, True), "duration_s": (float, True),
    "initial_drum_temp_C": (float, False), "mu_drum": (float, False), "tyre_road_mu": (float, False),
    "params": (str, False), "regulation": (str, False), "parameters": (dict, False),
}


def _validate(s: Scenario, where: str) -> None:
    if invalid_grade(s.grade_pct):
        raise UserError(f"{where}: key 'grade_pct' = {s.grade_pct:g} is outside (−100, 100]; give percent, e.g. 20")
    check_choice(s.direction, DIRECTIONS, f"direction in {where} (key 'direction')")
    if not (0 <= s.occupants <= MAX_OCCUPANTS):
        raise UserError(f"{where}: key 'occupants' = {s.occupants} must be a whole number from 0 to {MAX_OCCUPANTS}")
    if invalid_hand_force(s.hand_force_N):
        raise UserError(f"{where}: key 'hand_force_N' = {s.hand_force_N:g} is outside [0, {MAX_HAND_FORCE_N:g}] N; "
                        f"give the lever force in newtons, e.g. 400")
    if not (0 < s.duration_s <= MAX_DURATION_S):      # also false for NaN
        raise UserError(f"{where}: key 'duration_s' = {s.duration_s:g} must be in (0, {MAX_DURATION_S:.0f}] seconds")


def scenario_from_mapping(data: dict, where: str = "scenario", base_dir: Path | None = None,
                          params: str | None = None) -> Scenario:
    """Validate a parsed TOML mapping into a :class:`Scenario`.

    *params* (a set name, parameter or model file; CLI ``--params``) replaces the file's ``params``
    key; the file's own overrides (``mu_drum``, ``[parameters]``, …) still apply on top.
    """
    for key in data:
        if key not in _KEYS:
            raise UserError(f"{where}: unknown key '{key}'{suggest(key, _KEYS)}; valid keys: {', '.join(_KEYS)}")
    for key, (typ, required) in _KEYS.items():
        if required and key not in data:
            raise UserError(f"{where}: missing key '{key}'; add it (see scenarios/*.toml for examples)")
        if key not in data:
            continue
        v = data[key]
        if isinstance(v, float) and not math.isfinite(v):
            raise UserError(f"{where}: key '{key}' = {v!r} is not a finite number; give a physical value")
        ok = (isinstance(v, (int, float)) and not isinstance(v, bool)) if typ is float else \
             (isinstance(v, int) and not isinstance(v, bool)) if typ is int else isinstance(v, typ)
        if not ok:
            kind = {float: "a number", int: "a whole number", str: "a quoted string", dict: "a [table]"}[typ]
            raise UserError(f"{where}: key '{key}' must be {kind}, got {v!r}")
    src = data.get("params") if params is None else params
    if params is None and src is not None and base_dir is not None and src.endswith(".toml"):
        src = str((base_dir / src))
    from rollaway.model.drum_model import load_model
    try:
        model = load_model(src)
    except UserError as exc:       # a mistake inside the referenced file also names this file and key
        if src is None:
            raise
        raise UserError(f"{where}, key 'params': {exc}") from None
    params = model.params
    overrides = [(k, v, f"{where} [parameters]") for k, v in data.get("parameters", {}).items()]
    overrides += [(k, data[k], where) for k in ("initial_drum_temp_C", "mu_drum", "tyre_road_mu") if k in data]
    if overrides:
        params = params.with_overrides(overrides)
        params = dataclasses.replace(params, name=params.name + "+overrides")
    reg = data.get("regulation")
    if reg is not None:
        check_choice(reg, PRESETS, f"regulation in {where} (key 'regulation')")
    s = Scenario(name=data["name"], grade_pct=float(data["grade_pct"]), direction=data["direction"],
                 occupants=int(data["occupants"]), hand_force_N=float(data["hand_force_N"]),
                 duration_s=float(data["duration_s"]), params=params, description=data.get("description", ""),
                 regulation=reg, source=where, model=model.with_params(params))
    _validate(s, where)
    return s


def load_scenario(path: str | Path, params: str | None = None) -> Scenario:
    """Read and validate a scenario TOML file (*params*: another drum model, see :func:`scenario_from_mapping`)."""
    path = Path(path)
    data = read_toml(path, "scenario file", "see scenarios/*.toml for examples")
    return scenario_from_mapping(data, where=str(path), base_dir=path.parent, params=params)


def preset_scenarios(preset_name: str) -> list[Scenario]:
    """The scenarios (one per direction) of a regulation preset, on the ``paper`` set."""
    pr = PRESETS[check_choice(preset_name, PRESETS, "regulation preset")]
    return [scenario_from_mapping({
        "name": f"{pr.name}-{d}", "description": pr.source, "grade_pct": pr.grade_pct, "direction": d,
        "occupants": pr.occupants, "hand_force_N": pr.hand_force_N, "duration_s": pr.duration_s,
        "initial_drum_temp_C": pr.initial_temp_C, "regulation": pr.name}, where=f"preset {pr.name}")
        for d in pr.directions]
