"""rollaway: will this parked car roll away?

Drum parking-brake model with cooling (Ishak et al. 2018, doi:10.22201/fi.25940732e.2018.19n1.004),
analytic hold checks against FMVSS 135 / UN R13-H, a MuJoCo roll-away simulator, sweeps, and
the identification of missing physics from bench data.

>>> import rollaway
>>> model = rollaway.DrumModel("paper")
>>> rollaway.hold(model, grade_pct=20, hand_force_N=400, direction="downhill", occupants=5).holds
True

The API (:mod:`rollaway.api`): :class:`DrumModel`, :func:`hold`, :func:`simulate`, :func:`sweep`,
:func:`check`, :func:`load_measurements`, :func:`diagnose`, :func:`fit`.  The names are imported
on first use, so ``import rollaway`` (and ``rollaway --help``) stays fast.  ``rollaway.hold`` and
``rollaway.sweep`` are also the packages of those jobs (``from rollaway.hold import
required_torque``); calling them calls the API functions.  So is ``rollaway.risk`` (the roll-away rate
of a production population, :func:`rollaway.api.risk`).
"""
__version__ = "0.1.0"

from rollaway import _moved

_moved.install()        # old import paths of the previous release still work, with a DeprecationWarning

_LAZY = {
    # the API: one function per job
    "DrumModel": "rollaway.model.drum_model", "load_model": "rollaway.model.drum_model", "HoldVerdict": "rollaway.hold",
    "simulate": "rollaway.api", "check": "rollaway.api", "load_measurements": "rollaway.api",
    "diagnose": "rollaway.api", "fit": "rollaway.api",
    # the paper's chain as plain functions, and parameter sets
    "BrakeSeries": "rollaway.model.brake", "drum_brake": "rollaway.model.brake", "BrakeParameters": "rollaway.model.parameters",
    "load_parameters": "rollaway.model.parameters", "paper": "rollaway.model.parameters",
    "export_fmu": "rollaway.api",     # the drum model as an FMI 2.0 co-simulation FMU
}
_CALLABLE_PACKAGES = ("hold", "sweep", "risk")     # packages that are also the API functions of the same name

__all__ = ["BrakeParameters", "BrakeSeries", "DrumModel", "HoldVerdict", "check", "diagnose", "drum_brake", "fit",
           "hold", "load_measurements", "load_model", "load_parameters", "paper", "simulate", "sweep", "__version__",
           "risk"]
__all__ += ["export_fmu"]


def __getattr__(name):
    import importlib
    if name in _CALLABLE_PACKAGES:
        return importlib.import_module(f"rollaway.{name}")     # sets rollaway.<name> itself
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rollaway' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
