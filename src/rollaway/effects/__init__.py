"""The effect catalogue: one module per physical effect, selected by validated name.

``CATALOGUE`` maps names to classes.  User effects are added with :func:`register_effect`,
:func:`load_effect_file` (a Python file, CLI ``--effect-file``) or the entry-point group
``rollaway.effects``.  Unknown names raise :class:`~rollaway.errors.UserError` with the
closest match.
"""
from __future__ import annotations

import importlib.util
import inspect
import sys
from importlib.metadata import entry_points
from pathlib import Path

from rollaway.effects.base import Effect, EffectParameter, ModelState
from rollaway.effects.cable_relaxation import CableRelaxation
from rollaway.effects.drum_radial_contraction import DrumRadialContraction
from rollaway.effects.friction_temperature import FrictionTemperature
from rollaway.effects.installation_gap import InstallationGap
from rollaway.effects.lining_creep import LiningCreep
from rollaway.effects.modulus_temperature import ModulusTemperature
from rollaway.effects.nonlinear_lining_stiffness import NonlinearLiningStiffness
from rollaway.effects.radiation_cooling import RadiationCooling
from rollaway.effects.shoe_thermal_lag import ShoeThermalLag
from rollaway.effects.torque_zero_offset import TorqueZeroOffset
from rollaway.errors import UserError, check_choice

ENTRY_POINT_GROUP = "rollaway.effects"

CATALOGUE: dict[str, type[Effect]] = {cls.name: cls for cls in (
    FrictionTemperature, DrumRadialContraction, ShoeThermalLag, RadiationCooling, LiningCreep,
    CableRelaxation, InstallationGap, ModulusTemperature, NonlinearLiningStiffness, TorqueZeroOffset)}
_USER: dict[str, type[Effect]] = {}
_entry_points_loaded = False


def _validate_class(cls, where: str) -> type[Effect]:
    if not (inspect.isclass(cls) and issubclass(cls, Effect)):
        raise UserError(f"{where}: {cls!r} is not a subclass of rollaway.effects.base.Effect")
    if not cls.name or not cls.name.isidentifier():
        raise UserError(f"{where}: effect class {cls.__name__} needs a 'name' that is a Python identifier")
    if not cls.parameters:
        raise UserError(f"{where}: effect '{cls.name}' declares no parameters; give at least one "
                        f"EffectParameter with unit, neutral value and bounds")
    return cls


def register_effect(cls: type[Effect], where: str = "register_effect()") -> type[Effect]:
    """Add a user effect class to the registry (also usable as a class decorator)."""
    cls = _validate_class(cls, where)
    if cls.name in CATALOGUE and CATALOGUE[cls.name] is not cls:
        raise UserError(f"{where}: effect name '{cls.name}' is taken by the catalogue; choose another name")
    _USER[cls.name] = cls
    return cls


def load_effect_file(path: str | Path) -> list[str]:
    """Import a Python file and register every Effect subclass defined in it; return their names."""
    path = Path(path)
    if not path.is_file():
        raise UserError(f"effect file '{path}' does not exist; give the path of a .py file defining an Effect "
                        f"subclass")
    mod_name = f"rollaway_user_effect_{abs(hash(str(path.resolve())))}"
    spec = importlib.util.spec_from_file_location(mod_name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[mod_name] = module
    try:
        spec.loader.exec_module(module)
    except Exception as exc:  # a user's file: report, don't crash
        raise UserError(f"{path}: importing the effect file failed: {type(exc).__name__}: {exc}") from None
    found = [obj for obj in vars(module).values()
             if inspect.isclass(obj) and issubclass(obj, Effect) and obj is not Effect
             and obj.__module__ == mod_name]
    if not found:
        raise UserError(f"{path}: defines no subclass of rollaway.effects.base.Effect")
    return [register_effect(cls, str(path)).name for cls in found]


def _load_entry_points() -> None:
    global _entry_points_loaded
    if _entry_points_loaded:
        return
    _entry_points_loaded = True
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        try:
            cls = ep.load()
        except Exception as exc:  # a broken plugin must not break the tool
            print(f"rollaway: warning: effect plugin '{ep.name}' failed to load: {exc}", file=sys.stderr)
            continue
        if ep.name not in CATALOGUE:
            register_effect(cls, f"entry point {ep.value}")


def available_effects() -> dict[str, type[Effect]]:
    """Catalogue plus registered user effects (entry points included)."""
    _load_entry_points()
    return {**CATALOGUE, **_USER}


def get_effect(name: str | type[Effect] | Effect) -> Effect:
    """An effect instance by name (validated, closest-match hint) or from a class/instance."""
    if isinstance(name, Effect):
        return name
    if inspect.isclass(name):
        return _validate_class(name, "get_effect()")()
    return available_effects()[check_choice(str(name), available_effects(), "effect")]()


__all__ = ["CATALOGUE", "Effect", "EffectParameter", "ModelState", "available_effects", "get_effect",
           "load_effect_file", "register_effect"]
