"""SciPy's compiled routines, loaded without their packages' ``__init__``.

Importing any part of :mod:`scipy.optimize` runs that package's ``__init__``: linear programming, the global
optimisers, :mod:`scipy.linalg`, :mod:`scipy.sparse` — about 0.4 s of every ``rollaway`` command's start on a
2-core machine, for the two compiled routines loading and diagnosing bench data call: MINPACK's ``lmder``
(:mod:`rollaway.identify.solver`) and Lawson–Hanson non-negative least squares (:mod:`rollaway.bench.noise`).
:func:`optimize_extension` loads such a compiled module from SciPy's files by itself; the routines are SciPy's
own, called as SciPy's Python wrappers call them (``scipy.optimize.leastsq``, ``scipy.optimize.nnls``).  Where the
file is not found, the ordinary import is used; where the installed SciPy's compiled ``nnls`` takes other arguments,
the public function: slower to start, the same numbers.

Likewise :mod:`scipy.special`'s ``__init__`` loads SciPy's array-API layer, which star-imports NumPy and so NumPy's
``f2py`` (with ``charset_normalizer``): about 0.3 s, for the four distribution functions loading and diagnosing
call (``ndtr``, ``stdtrit``, ``fdtri``, ``fdtrc``; ``chdtri`` for raw logs).  :func:`special_functions` returns
SciPy's compiled ufunc module ``scipy.special._ufuncs`` — the very objects ``scipy.special`` exports — loaded
without that ``__init__``; a later ``import scipy.special`` takes it from :data:`sys.modules`.
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


def special_functions():
    """SciPy's compiled special-function ufuncs (``scipy.special._ufuncs``: ``ndtr``, ``stdtrit``, ``fdtri``,
    ``fdtrc``, ``chdtri``, … — the objects :mod:`scipy.special` exports), without running :mod:`scipy.special`'s
    ``__init__``; :mod:`scipy.special` itself where it is already imported or the direct load fails.

    The extension imports its sibling extensions through the package (``scipy.special._special_ufuncs``, …): for
    that moment, under the import lock, ``scipy.special`` is a bare package object whose path is SciPy's folder
    (so those siblings load from their files and nothing else runs); then it is removed, so a later ``import
    scipy.special`` runs the real package, which finds the loaded extensions in :data:`sys.modules`."""
    done = sys.modules.get("scipy.special")
    if done is not None and not getattr(done, "_rollaway_bare", False):
        return done
    mod = sys.modules.get("scipy.special._ufuncs")
    if mod is not None:
        return mod
    import importlib
    import importlib.machinery
    import os
    import types

    import _imp

    import scipy
    folder = os.path.join(os.path.dirname(scipy.__file__), "special")
    bare = types.ModuleType("scipy.special")
    bare.__spec__ = importlib.machinery.ModuleSpec("scipy.special", None, is_package=True)
    bare.__spec__.submodule_search_locations = bare.__path__ = [folder]
    bare.__package__, bare._rollaway_bare = "scipy.special", True
    _imp.acquire_lock()
    try:
        if "scipy.special" in sys.modules:                # imported meanwhile: the package itself
            return sys.modules["scipy.special"]
        sys.modules["scipy.special"] = scipy.special = bare
        try:
            mod = importlib.import_module("scipy.special._ufuncs")
        except ImportError:
            mod = None
        finally:
            if sys.modules.get("scipy.special") is bare:
                del sys.modules["scipy.special"]
            if scipy.__dict__.get("special") is bare:
                del scipy.special
    finally:
        _imp.release_lock()
    if mod is None:
        import scipy.special as mod
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


__all__ = ["nnls", "optimize_extension", "special_functions"]
