"""Import paths of the previous release, kept working for one release with a DeprecationWarning.

The modules moved when the code was cut into one package per job (docs/development.md, "where
things are").  :data:`MOVED` maps each old module path to its new one; :class:`MovedFinder`
(installed by ``rollaway/__init__.py``) answers an import of an old path with the new module
itself (the same object, so patches and ``isinstance`` agree) and warns once, naming the new path.
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

MOVED = {
    "rollaway.parameters": "rollaway.model.parameters",
    "rollaway.drum_parameters": "rollaway.model.drum_parameters",
    "rollaway.chain": "rollaway.model.chain",
    "rollaway.model_file": "rollaway.model.model_file",
    "rollaway.covariance": "rollaway.model.covariance",
    "rollaway.brake": "rollaway.model.brake",
    "rollaway.predictive": "rollaway.uncertainty.predictive",
    "rollaway.scenario": "rollaway.hold.scenario",
    "rollaway.regulations": "rollaway.hold.regulations",
    "rollaway.compliance": "rollaway.sweep.compliance",
    "rollaway.identify.bands": "rollaway.uncertainty.bands",
    "rollaway.identify.calibration_check": "rollaway.uncertainty.calibration_check",
    "rollaway.figures.ladder": "rollaway.identify.ladder_plot",
    **{f"rollaway.identify.{m}": f"rollaway.bench.{m}"
       for m in ("sources", "columns", "asam_mdf", "batch", "reduction", "rawnoise", "measurements", "noise")},
}


def warn_moved(old: str, new: str, stacklevel: int = 3) -> None:
    warnings.warn(f"{old} has moved to {new}; the old path goes in the next release", DeprecationWarning,
                  stacklevel=stacklevel)


class MovedFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds the old paths of :data:`MOVED`; loading one puts the new module in its place."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname not in MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        old = module.__name__
        new = importlib.import_module(MOVED[old])
        warn_moved(old, MOVED[old], stacklevel=2)
        sys.modules[old] = new        # the import system returns what sys.modules holds after exec_module


def lazy_getattr(package: str, names: dict[str, str], moved: dict[str, str] | None = None):
    """A module ``__getattr__`` importing *names* (name → module) on first use; names in *moved*
    (name → new module) also warn that the old place goes."""
    moved = moved or {}

    def __getattr__(name):
        if name in names:
            return getattr(importlib.import_module(names[name]), name)
        if name in moved:
            warn_moved(f"{package}.{name}", f"{moved[name]}.{name}")
            return getattr(importlib.import_module(moved[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__


def install() -> None:
    if not any(isinstance(f, MovedFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, MovedFinder())
