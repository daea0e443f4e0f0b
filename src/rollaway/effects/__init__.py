"""The effect catalogue: one module per physical effect, selected by validated name.

``CATALOGUE`` maps names to classes.  User effects are added with :func:`register_effect`,
:func:`load_effect_file` (a Python file, CLI ``--effect-file``) or the entry-point group
``rollaway.effects``.  Unknown names raise :class:`~rollaway.errors.UserError` with the
closest match.
"""
from __future__ import annotations

import importlib.util
import inspect
import math
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
HOOKS = ("drum_temperature", "lining_temperature", "displacement", "lining_modulus", "gap", "clamp_force",
         "friction")
_entry_points_loaded = False


def _validate_class(cls, where: str) -> type[Effect]:
    """Check a user's Effect subclass: a name that is an identifier, parameters with bounds, hooks callable."""
    if not (inspect.isclass(cls) and issubclass(cls, Effect)):
        raise UserError(f"{where}: {cls!r} is not a subclass of rollaway.effects.base.Effect")
    label = f"effect class {getattr(cls, '__name__', '?')}"
    name = getattr(cls, "name", None)
    if not isinstance(name, str) or not name.isidentifier():
        raise UserError(f"{where}: {label} needs a 'name' that is a text Python identifier, e.g. name = \"humidity\"; "
                        f"got {name!r}"[:300])
    params = getattr(cls, "parameters", None)
    if not isinstance(params, tuple) or not params:
        raise UserError(f"{where}: effect '{name}' declares no parameters (a tuple of EffectParameter); give at least "
                        f"one EffectParameter with unit, neutral value and bounds")
    seen = set()
    for p in params:
        if not isinstance(p, EffectParameter):
            raise UserError(f"{where}: effect '{name}': parameters must be EffectParameter(...) entries, got {p!r}"[:300])
        if not isinstance(p.name, str) or not p.name.isidentifier() or p.name in seen:
            raise UserError(f"{where}: effect '{name}': parameter name {p.name!r} must be a unique Python identifier")
        seen.add(p.name)
        bounds = (p.lower, p.upper, p.neutral, p.initial)
        if not all(isinstance(b, (int, float)) and not isinstance(b, bool) and math.isfinite(b) for b in bounds):
            raise UserError(f"{where}: effect '{name}': parameter '{p.name}' needs finite numeric bounds, neutral "
                            f"and initial values")
    amplitude = getattr(cls, "amplitude", "")
    if amplitude not in ("", *seen):
        raise UserError(f"{where}: effect '{name}': amplitude = {amplitude!r} is not one of its parameters "
                        f"({', '.join(sorted(seen))}); name the parameter whose neutral value switches it off, or "
                        f"leave it out"[:300])
    scale = getattr(cls, "shape_scale", 0.0)
    if not (isinstance(scale, (int, float)) and not isinstance(scale, bool) and math.isfinite(scale) and scale >= 0):
        raise UserError(f"{where}: effect '{name}': shape_scale = {scale!r} must be a number ≥ 0 (the unit of an "
                        f"absolute change of its hook's quantity), or left out"[:300])
    for hook in HOOKS:
        if not callable(getattr(cls, hook, None)):
            raise UserError(f"{where}: effect '{name}': '{hook}' must be a method (a hook), got "
                            f"{getattr(cls, hook, None)!r}"[:300])
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
    from rollaway.effects.preflight import preflight_import
    preflight_import(path)          # os._exit(), a crash or an endless loop at import: an error, not our end
    try:
        spec = importlib.util.spec_from_file_location(mod_name, path)
        if spec is None or spec.loader is None:
            raise ImportError("not a Python source file")
        module = importlib.util.module_from_spec(spec)
        sys.modules[mod_name] = module
        spec.loader.exec_module(module)
    except KeyboardInterrupt:
        raise
    except SystemExit as exc:   # sys.exit() in a plugin must not end the tool (a silent pass in CI)
        sys.modules.pop(mod_name, None)
        raise UserError(f"{path}: the effect file called sys.exit({exc.code!r}) while being imported; "
                        f"a plugin must only define Effect classes") from None
    except BaseException as exc:  # noqa: BLE001 - a user's file: report, don't crash
        sys.modules.pop(mod_name, None)
        where = _plugin_line(exc, path)
        text = " ".join(str(exc).split())[:200]
        raise UserError(f"{path}{where}: importing the effect file failed: {type(exc).__name__}: {text}; "
                        f"fix the plugin") from None
    found = [obj for obj in vars(module).values()
             if inspect.isclass(obj) and issubclass(obj, Effect) and obj is not Effect
             and obj.__module__ == mod_name]
    if not found:
        raise UserError(f"{path}: defines no subclass of rollaway.effects.base.Effect")
    names = [getattr(cls, "name", None) for cls in found]
    for cls in found:
        _validate_class(cls, str(path))
    dup = next((n for n in names if names.count(n) > 1), None)
    if dup is not None:
        raise UserError(f"{path}: two effect classes are named '{dup}'; give each a unique name")
    for cls in found:
        cls.__rollaway_source__ = str(path)   # named in the errors of its hooks
    return [register_effect(cls, str(path)).name for cls in found]


def _plugin_line(exc: BaseException, path: Path) -> str:
    """', line N' of the plugin's frame where *exc* was raised (or '')."""
    if isinstance(exc, SyntaxError) and exc.lineno:
        return f", line {exc.lineno}"
    tb, line = exc.__traceback__, None
    target = str(path.resolve())
    while tb is not None:
        if str(Path(tb.tb_frame.f_code.co_filename).resolve()) == target:
            line = tb.tb_lineno
        tb = tb.tb_next
    return f", line {line}" if line else ""


def _load_entry_points() -> None:
    global _entry_points_loaded
    if _entry_points_loaded:
        return
    _entry_points_loaded = True
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        try:
            cls = ep.load()
            if ep.name not in CATALOGUE:
                register_effect(cls, f"entry point {ep.value}")
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # noqa: BLE001 - a broken plugin (even one calling sys.exit) must not break the tool
            print(f"rollaway: warning: effect plugin '{ep.name}' ({ep.value}) failed to load: "
                  f"{type(exc).__name__}: {exc}", file=sys.stderr)


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
