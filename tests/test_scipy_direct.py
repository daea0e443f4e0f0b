"""SciPy's compiled routines loaded without scipy.optimize's and scipy.special's packages: the same numbers, and the
packages not imported."""
import os
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from rollaway import scipy_direct


@settings(max_examples=200, deadline=None)
@given(st.integers(3, 30), st.integers(0, 2 ** 31), st.floats(-3.0, 3.0), st.floats(-3.0, 3.0))
def test_nnls_is_scipys_bit_for_bit(rows, seed, a, b):
    """Interior or on either edge (true coefficients of either sign, noisy targets, columns of unlike scale)."""
    from scipy.optimize import nnls
    rng = np.random.default_rng(seed)
    level = rng.uniform(0.0, 900.0, rows)
    design = np.column_stack([np.ones(rows), level ** 2]) * rng.uniform(0.5, 2.0, rows)[:, None]
    target = design @ np.array([a, b * 1e-6]) + rng.normal(0.0, 0.3, rows)
    got = scipy_direct.nnls(design, target)
    assert np.all(got >= 0)
    assert np.array_equal(got, nnls(design, target)[0])


def test_a_compiled_module_is_loaded_once_and_kept_for_scipy_optimize():
    mod = scipy_direct.optimize_extension("_minpack")
    assert scipy_direct.optimize_extension("_minpack") is mod
    from scipy.optimize import _minpack
    assert _minpack is mod


def test_nnls_of_a_bad_design_is_scipys_error():
    with pytest.raises(ValueError):
        scipy_direct.nnls(np.array([[1.0, np.nan], [1.0, 2.0]]), np.array([1.0, 2.0]))


def test_diagnosing_a_log_does_not_import_scipy_optimize(tmp_path):
    """Loading and diagnosing bench data needs MINPACK and nnls, not scipy.optimize's package (about 0.4 s of every
    command's start)."""
    from rollaway.identify.synth import synth
    path = tmp_path / "bench.csv"
    synth(["lining_creep"], seed=3, hand_forces_N=(200.0, 300.0), dt_s=300.0).to_csv(path)
    code = ("import sys; from rollaway.api import load_measurements, diagnose; "
            f"d = diagnose(load_measurements({str(path)!r})); "
            "print(sorted(m for m in sys.modules if m.startswith('scipy.optimize'))); "
            "print(sorted(m for m in ('scipy.special', 'scipy.stats', 'numpy.f2py') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, "ROLLAWAY_WORKERS": "1"})
    assert out.returncode == 0, out.stderr[-2000:]
    optimize, packages = out.stdout.strip().splitlines()
    assert optimize == "['scipy.optimize._minpack', 'scipy.optimize._slsqplib']", out.stdout
    assert packages == "[]", out.stdout          # scipy.special's ufuncs came without its package (0.3 s)


def _fresh(code: str) -> str:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.strip()


def test_special_functions_are_scipys_objects_and_scipy_special_still_imports():
    """Loaded first without the package, then the package imported: the same ufunc objects, scipy.stats working,
    and scipy.special's own attributes (not only the ufuncs) there."""
    code = ("import sys; from rollaway.scipy_direct import special_functions; sf = special_functions(); "
            "bare = 'scipy.special' in sys.modules; "
            "import scipy.special, scipy.stats; "
            "same = all(getattr(sf, n) is getattr(scipy.special, n) for n in ('ndtr', 'stdtrit', 'fdtri', 'fdtrc', 'chdtri')); "
            "print(bare, same, special_functions() is scipy.special, callable(scipy.special.logsumexp), "
            "repr(float(scipy.stats.t.ppf(0.975, 5))), repr(float(sf.stdtrit(5, 0.975))))")
    bare, same, package, logsumexp, public, direct = _fresh(code).split()
    assert (bare, same, package, logsumexp) == ("False", "True", "True", "True")
    assert public == direct


@settings(max_examples=50, deadline=None)
@given(st.floats(0.5, 200.0), st.floats(0.5, 200.0), st.floats(1e-6, 1 - 1e-6))
def test_special_functions_give_scipy_specials_numbers(d1, d2, p):
    import scipy.special as public
    sf = scipy_direct.special_functions()
    for name, args in (("ndtr", (d1 - 100.0,)), ("stdtrit", (d1, p)), ("fdtri", (d1, d2, p)), ("fdtrc", (d1, d2, p * 10)),
                       ("chdtri", (d1, p))):
        assert np.array_equal(getattr(sf, name)(*args), getattr(public, name)(*args), equal_nan=True)
