"""MINPACK's Levenberg–Marquardt as the fits call it, and the test that gives up a fit which cannot reach its bar."""
import numpy as np
import pytest

from rollaway.identify import solver
from rollaway.identify.calibrate import calibrate
from tests.identify.bench_generator import generate


@pytest.mark.parametrize("seed", range(4))
def test_levenberg_marquardt_is_least_squares_lm_without_its_last_jacobian(seed):
    """The same iterates and answer as scipy's least_squares(method="lm", x_scale=1.0) with the same forward
    differences evaluated side by side, bit for bit, with one Jacobian fewer (least_squares evaluates one after
    MINPACK returns); the residual's calls at a point MINPACK asks for twice are not repeated."""
    from scipy.optimize import least_squares
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 4.0, 40)
    y = 3.0 * np.exp(-0.7 * t) + 0.5 * np.sin(2.0 * t) + rng.normal(0, 0.02, t.size)
    calls = {"fun": 0, "columns": 0}

    def fun(z):
        calls["fun"] += 1
        return z[0] * np.exp(-z[1] * t) + z[2] * np.sin(z[3] * t) - y

    def columns(_f, zs):
        calls["columns"] += 1
        return [fun(z) for z in zs]

    z0 = np.array([1.0, 0.2, 0.1, 1.5]) + rng.normal(0, 0.05, 4)
    ref = least_squares(fun, z0, method="lm", xtol=1e-6, ftol=1e-6, gtol=1e-6, x_scale=1.0, max_nfev=100,
                        workers=columns)
    ref_columns = calls["columns"]
    calls.update(fun=0, columns=0)
    z, gave_up = solver.levenberg_marquardt(fun, columns, z0, 1e-6, 100)
    assert not gave_up
    assert np.array_equal(z, ref.x)
    assert calls["columns"] == ref_columns - 1
    assert calls["fun"] - 4 * calls["columns"] <= ref.nfev      # the residual at each point once


@pytest.mark.parametrize("seed", range(3))
def test_a_screen_that_cannot_reach_its_bar_is_given_up_and_one_that_can_is_untouched(seed):
    """A misfit screen (a modulus law for a creeping, radiating drum: it crawls to its budget) against a bar far
    below its end (the right pair's BIC) is abandoned early (within a third of the full fit's evaluations), above
    the bar; with the bar FUTILE_MARGIN above its end (a caller's bar is its threshold plus that margin) the fit is
    the same bit for bit: the projection never stops a fit that would have come below the caller's threshold."""
    data = generate(["creep_exponential", "radiation"], sampling="1min", seed=50 + seed, n_forces=4)
    kw = dict(statistics=False, max_iterations=6)
    best = calibrate(data, ["lining_creep", "radiation_cooling"], **kw)
    full = calibrate(data, ["modulus_temperature", "radiation_cooling"], **kw)
    assert full.bic > best.bic + 500.0                                  # the misfit is far from the truth's law
    same = calibrate(data, ["modulus_temperature", "radiation_cooling"], give_up_bic=full.bic + solver.FUTILE_MARGIN,
                     **kw)
    assert "gave_up" not in same.fit_info
    for k in full.values:
        assert np.array_equal(np.asarray(full.values[k]), np.asarray(same.values[k])), k
    cut = calibrate(data, ["modulus_temperature", "radiation_cooling"], give_up_bic=best.bic + 20.0, **kw)
    assert cut.fit_info.get("gave_up") == best.bic + 20.0 and cut.bic > best.bic + 20.0
    assert cut.fit_info["stages"][0]["nfev"] < full.fit_info["stages"][0]["nfev"] / 3
