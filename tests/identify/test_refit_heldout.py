"""rollaway.identify.refit_heldout: held-out residuals that refit the folds where the linearisation fails, on data
the model code did not make (tests/identify/bench_generator.py)."""
import numpy as np
import pytest

from rollaway.identify.calibrate import calibrate
from rollaway.identify.refit_heldout import FOLD_ITERATIONS, _fold, linear_holds, refit_loto_residuals
from rollaway.uncertainty.heldout import folds, loto_residuals
from tests.identify.bench_generator import OTHER_DRUMS, generate


def _with_noise(data, torque_Nm=8.0, temp_C=1.5):
    data.torque_sigma_Nm = np.full(len(data), torque_Nm)
    data.temp_sigma_C = np.full(len(data), temp_C)
    return data


def _chi2(data, r):
    return np.bincount(np.concatenate([data.test_index, data.test_index]), r * r, data.n_tests)


def _refitted(fit) -> np.ndarray:
    """Every fold refitted (what refit_loto_residuals does to the folds whose linear step fails)."""
    d = fit.data
    out = np.empty(2 * len(d))
    start = {k: v for k, v in fit.values.items() if np.ndim(v) == 0}
    for held in folds(d.n_tests):
        f = _fold(d, held, fit.model, fit.names, start, FOLD_ITERATIONS)
        out[f.rows] = f.residual
    return out


@pytest.mark.parametrize("hidden,effect,seed", [("friction_linear", "friction_temperature", 3),
                                                ("creep_exponential", "lining_creep", 4)])
def test_a_refitted_fold_agrees_with_the_linear_step_where_the_model_is_well_determined(hidden, effect, seed):
    """Eight tests, the effect in its catalogue form: one Woodbury step is close to a refit, so the two held-out
    χ² per test agree (a fold placed on the wrong rows, or a held-out test's T_0 not refitted, would not), and the
    check of each linear step keeps nearly all of them."""
    data = _with_noise(generate([hidden], sampling="5min", seed=seed, drum=OTHER_DRUMS["arm_80mm"]))
    fit = calibrate(data, [effect])
    refit, linear = _chi2(data, _refitted(fit)), _chi2(data, loto_residuals(fit))
    own = _chi2(data, np.concatenate([(fit.prediction.drum_temp_C - data.drum_temp_C) / data.temp_sigma_C,
                                      (fit.prediction.torque_Nm - data.torque_Nm) / data.torque_sigma_Nm]))
    assert data.n_tests == 8
    np.testing.assert_allclose(refit, linear, rtol=0.03)     # within 1.1 % measured
    assert refit.sum() > own.sum()                            # a test left out is predicted worse than fitted
    held, refitted = refit_loto_residuals([fit])
    assert refitted[0] <= 1                    # a check may refit a fold it need not have (0, 1 measured)
    np.testing.assert_allclose(_chi2(data, held[0]), linear, rtol=0.03)


def test_a_fold_the_linear_step_fails_is_refitted_and_only_that_one():
    """A modulus spline (8 segments of the lining temperature) on three tests, one direction: the hottest test
    alone informs the top segments, and leaving it out fails the linear step's check; that fold, and only that
    one, comes back refitted, and the refit predicts it better than the linear step (which overshoots)."""
    from rollaway.effects import get_effect
    from rollaway.identify.shape import flexible_effect
    data = _with_noise(generate(["modulus_sigmoid"], sampling="5min", seed=0, n_forces=3, directions=("downhill",)))
    fit = calibrate(data, [flexible_effect(get_effect("modulus_temperature"), data.drum_temp_C)])
    checks = [linear_holds(fit, h) for h in folds(data.n_tests)]
    assert checks.count(False) >= 1
    held, refitted = refit_loto_residuals([fit])
    assert refitted == [checks.count(False)]
    full, linear = _refitted(fit), loto_residuals(fit)
    for h, ok in zip(folds(data.n_tests), checks):
        rows = np.isin(np.concatenate([data.test_index, data.test_index]), h)
        np.testing.assert_array_equal(held[0][rows], (linear if ok else full)[rows])
        if not ok:
            assert (full[rows] ** 2).sum() < (linear[rows] ** 2).sum()


def test_a_single_test_keeps_its_linear_step():
    """Leaving the only test out leaves nothing to refit on."""
    data = _with_noise(generate(["creep_exponential"], sampling="15min", seed=7, n_forces=1,
                                directions=("downhill",), forces=[300.0]))
    fit = calibrate(data, ["lining_creep"])
    held, refitted = refit_loto_residuals([fit])
    assert data.n_tests == 1 and refitted == [0]
    np.testing.assert_array_equal(held[0], loto_residuals(fit))


def test_every_fit_gets_its_own_folds_and_a_fit_without_globals_keeps_its_residual():
    data = _with_noise(generate(["friction_linear"], sampling="15min", seed=5, n_forces=2))
    a, b = calibrate(data, ["friction_temperature"]), calibrate(data, ["lining_creep"])
    fixed = calibrate(data, (), free=[])
    (ra, rb, rf), _ = refit_loto_residuals([a, b, fixed])
    assert not np.allclose(ra, rb)
    np.testing.assert_array_equal(ra, refit_loto_residuals([a])[0][0])
    np.testing.assert_allclose(rf, np.concatenate([(fixed.prediction.drum_temp_C - data.drum_temp_C) / 1.5,
                                                   (fixed.prediction.torque_Nm - data.torque_Nm) / 8.0]))


def test_the_same_refits_on_one_core(monkeypatch):
    data = _with_noise(generate(["creep_exponential"], sampling="15min", seed=6, n_forces=2))
    fit = calibrate(data, ["lining_creep"])
    both = _refitted(fit)
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    np.testing.assert_array_equal(_refitted(fit), both)


def test_a_fold_the_solver_cannot_refit_keeps_its_linear_step(monkeypatch):
    from rollaway.effects import get_effect
    from rollaway.identify import calibrate as calibrate_module
    from rollaway.identify.shape import flexible_effect
    data = _with_noise(generate(["modulus_sigmoid"], sampling="5min", seed=0, n_forces=3, directions=("downhill",)))
    fit = calibrate(data, [flexible_effect(get_effect("modulus_temperature"), data.drum_temp_C)])
    real = calibrate_module.calibrate

    def failing(*args, **kwargs):
        if kwargs.get("max_iterations") == FOLD_ITERATIONS:
            raise ValueError("Method 'lm' doesn't work when the number of residuals is less than the number of "
                             "variables.")
        return real(*args, **kwargs)
    monkeypatch.setattr(calibrate_module, "calibrate", failing)
    held, refitted = refit_loto_residuals([fit])
    assert refitted == [0]
    np.testing.assert_array_equal(held[0], loto_residuals(fit))


def test_a_fold_whose_refit_runs_away_keeps_its_linear_step(monkeypatch):
    """A refitted fold whose model has no finite prediction of the held-out test (a refit that ran away) is no
    score: its infinite χ² would decide the comparison alone.  It keeps its linear step, as a fold the solver cannot
    take does; the folds that refit to a finite prediction are kept refitted."""
    from rollaway.effects import get_effect
    from rollaway.identify import refit_heldout
    from rollaway.identify.shape import flexible_effect
    data = _with_noise(generate(["modulus_sigmoid"], sampling="5min", seed=0, n_forces=3, directions=("downhill",)))
    fit = calibrate(data, [flexible_effect(get_effect("modulus_temperature"), data.drum_temp_C)])
    checks = [linear_holds(fit, h) for h in folds(data.n_tests)]
    real, seen = refit_heldout._at, []

    def running_away(d, model, values):          # the first refitted fold's prediction (not a check's) runs away
        out = real(d, model, values)
        if len(d) < len(data):
            seen.append(len(seen))
        return np.where(np.arange(out.size) == 0, np.inf, out) if seen == [0] and len(d) < len(data) else out
    monkeypatch.setattr(refit_heldout, "_at", running_away)
    held, refitted = refit_loto_residuals([fit])
    assert checks.count(False) >= 1 and refitted == [checks.count(False) - 1]
    assert np.all(np.isfinite(held[0]))
    first = np.isin(np.concatenate([data.test_index, data.test_index]), folds(data.n_tests)[checks.index(False)])
    np.testing.assert_array_equal(held[0][first], loto_residuals(fit)[first])


def test_a_calibration_asked_next_is_fitted_beside_the_refitted_folds_and_kept(monkeypatch):
    """*also*: the folds come back as without it, and the calibration the caller asks for next is then served by
    the memo (no fit of its own), equal to one fitted alone."""
    from rollaway.effects import get_effect
    from rollaway.identify import calibrate as calibrate_module
    from rollaway.identify.memo import fit_memo
    from rollaway.identify.shape import flexible_effect
    data = _with_noise(generate(["modulus_sigmoid"], sampling="5min", seed=0, n_forces=3, directions=("downhill",)))
    fit = calibrate(data, [flexible_effect(get_effect("modulus_temperature"), data.drum_temp_C)])
    job = (["lining_creep"], None, dict(start={"mu_drum": 0.35}, max_iterations=4))
    alone = calibrate(data, *job[:2], **job[2])
    plain = refit_loto_residuals([fit])
    with fit_memo():
        fit._refit_heldout = None
        held, refitted = refit_loto_residuals([fit], also=[job])
        assert refitted == plain[1] and refitted[0] >= 1
        np.testing.assert_array_equal(held[0], plain[0][0])
        monkeypatch.setattr(calibrate_module, "_calibrate", lambda *a, **k: pytest.fail("fitted again"))
        kept = calibrate(data, *job[:2], **job[2])
    assert kept.bic == alone.bic and kept.values.keys() == alone.values.keys()
