"""rollaway: will this parked car roll away?

Drum parking-brake model with cooling (Ishak et al. 2018, doi:10.22201/fi.25940732e.2018.19n1.004),
analytic hold checks against FMVSS 135 / UN R13-H, and a MuJoCo roll-away simulator.

The names below are imported on first use, so ``import rollaway`` (and ``rollaway --help``)
stays fast.
"""
__version__ = "0.1.0"

_LAZY = {"BrakeSeries": "rollaway.brake", "drum_brake": "rollaway.brake", "BrakeParameters": "rollaway.parameters",
         "load_parameters": "rollaway.parameters", "paper": "rollaway.parameters"}

__all__ = ["BrakeParameters", "BrakeSeries", "drum_brake", "load_parameters", "paper", "__version__"]


def __getattr__(name):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rollaway' has no attribute {name!r}")
