"""SciPy's compiled optimisation routines, loaded without :mod:`scipy.optimize`'s package.

Importing any part of :mod:`scipy.optimize` runs that package's ``__init__``: linear programming, the global
optimisers, :mod:`scipy.linalg`, :mod:`scipy.sparse` — about 0.4 s of every ``rollaway`` command's start on a
2-core machine, for the two compiled routines loading and diagnosing bench data call: MINPACK's ``lmder``
(:mod:`rollaway.identify.solver`) and Lawson–Hanson non-negative least squares (:mod:`rollaway.bench.noise`).
:func:`optimize_extension` loads such a compiled module from SciPy's files by itself; the routines are SciPy's
own, called as SciPy's Python wrappers call them (``scipy.optimize.leastsq``, ``scipy.optimize.nnls``).  Where the
file is not found, the ordinary import is used; where the installed SciPy's compiled ``nnls`` takes other arguments,
the public function: slower to start, the same numbers.
"""
from __future__ import annotations

import sys

import numpy as np


def optimize_extension(name: str):
    """The compiled module ``scipy.optimize.<name>`` (e.g. ``_minpack``), loaded from its file without
    :mod:`scipy.optimize`'s ``__init__`` and registered under its own name (a later ``import scipy.optimize`` takes
    it from there); through the package where its file is not found."""
    full = f"scipy.optimize.{name}"
    mod = sys.modules.get(full)
    if mod is not None:
        return mod
    try:
        import glob
        import importlib.machinery
        import importlib.util
        import os

        import scipy
        found = sorted(glob.glob(os.path.join(os.path.dirname(scipy.__file__), "optimize", f"{name}.*")))
        path = next(p for p in found if p.endswith(tuple(importlib.machinery.EXTENSION_SUFFIXES)))
        loader = importlib.machinery.ExtensionFileLoader(full, path)
        mod = importlib.util.module_from_spec(importlib.util.spec_from_file_location(full, path, loader=loader))
        loader.exec_module(mod)
    except (ImportError, OSError, StopIteration):
        import importlib
        return importlib.import_module(full)
    sys.modules[full] = mod
    return mod


def nnls(design: np.ndarray, target: np.ndarray) -> np.ndarray:
    """:func:`scipy.optimize.nnls` (``design @ x ≈ target``, x ≥ 0; its default iteration limit, 3 × columns):
    the same compiled routine, called as it calls it."""
    a = np.asarray_chkfinite(design, dtype=np.float64, order="C")
    b = np.asarray_chkfinite(target, dtype=np.float64)
    try:
        x, _, info = optimize_extension("_slsqplib").nnls(a, b, 3 * a.shape[1])
    except (ImportError, AttributeError, TypeError, ValueError):       # another SciPy: its public function
        from scipy.optimize import nnls as public
        return public(a, b)[0]
    if info == 3:
        raise RuntimeError("Maximum number of iterations reached.")
    return x


__all__ = ["nnls", "optimize_extension"]
