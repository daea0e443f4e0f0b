"""rollaway.identify.intervals: effective sample size, mixture variances, restated intervals — against
closed forms and on data the model code did not make (AR(1) series; the independent bench generator)."""
from types import SimpleNamespace

import numpy as np
import pytest

from rollaway.identify.calibrate import ParameterEstimate
from rollaway.identify.intervals import MAX_RHO, ess_inflation, lag1, mixture_variances, restate
from rollaway.model.covariance import Covariance


def _fit_with_residuals(res_torque, tests=4, res_temp=None):
    """A stand-in fit: *res_torque* split evenly into *tests* tests (σ = 1 on both channels)."""
    n = len(res_torque)
    d = SimpleNamespace(test_index=np.repeat(np.arange(tests), n // tests), n_tests=tests,
                        time_s=np.tile(np.arange(n // tests, dtype=float), tests),
                        torque_sigma_Nm=np.ones(n), temp_sigma_C=np.ones(n))
    rt = np.zeros(n) if res_temp is None else res_temp
    return SimpleNamespace(data=d, residuals=lambda: (rt, np.asarray(res_torque, float)))


def _ar1(rng, rho, n):
    e = rng.standard_normal(n)
    x = np.empty(n)
    x[0] = e[0] / np.sqrt(1 - rho ** 2)
    for i in range(1, n):
        x[i] = rho * x[i - 1] + e[i]
    return x


@pytest.mark.parametrize("rho", [0.0, 0.5, 0.8])
def test_lag1_recovers_the_autocorrelation_of_ar1_series(rho):
    rng = np.random.default_rng(1)
    est = [lag1(_fit_with_residuals(np.concatenate([_ar1(rng, rho, 500) for _ in range(4)])), "torque")
           for _ in range(20)]
    assert abs(np.mean(est) - rho) < 0.03, (rho, np.mean(est))


def test_inflation_is_the_closed_form_and_capped():
    rng = np.random.default_rng(2)
    x = np.concatenate([_ar1(rng, 0.6, 2000) for _ in range(4)])
    k = ess_inflation(_fit_with_residuals(x))
    rho = lag1(_fit_with_residuals(x), "torque")
    assert k["torque"] == pytest.approx((1 + rho) / (1 - rho)) and k["temperature"] == 1.0
    smooth = np.tile(np.linspace(-1, 1, 400), 4)              # one smooth curve: ρ → 1, capped
    assert ess_inflation(_fit_with_residuals(smooth))["torque"] == pytest.approx((1 + MAX_RHO) / (1 - MAX_RHO))


def test_inflated_interval_of_a_mean_covers_95_percent_of_ar1_series():
    """The 95 % interval of the mean of an AR(1) series: σ̂/√n alone covers far less; with the inflation
    (1 + ρ̂)/(1 − ρ̂) it covers 0.92–0.98 over 400 series (the large-n variance of the mean of AR(1) is
    σ²/(n(1 − ρ)²) = σ_x²(1 + ρ)/(n(1 − ρ)))."""
    rng = np.random.default_rng(3)
    naive = honest = 0
    trials = 400
    for _ in range(trials):
        x = _ar1(rng, 0.7, 800) + 2.0
        se = x.std(ddof=1) / np.sqrt(x.size)
        k = ess_inflation(_fit_with_residuals(x - x.mean(), tests=1))["torque"]
        naive += abs(x.mean() - 2.0) <= 1.96 * se
        honest += abs(x.mean() - 2.0) <= 1.96 * se * np.sqrt(k)
    assert naive / trials < 0.7
    assert 0.92 <= honest / trials <= 0.98, honest / trials


def test_mixture_variance_is_the_law_of_total_variance():
    sel = SimpleNamespace(values={"mu_drum": 0.40}, covariance=Covariance(("mu_drum",), [[1e-4]]))
    alt = SimpleNamespace(values={"mu_drum": 0.43}, covariance=Covariance(("mu_drum",), [[4e-4]]))
    v = mixture_variances(sel, [(0.25, alt)])["mu_drum"]
    assert v == pytest.approx(0.75 * 1e-4 + 0.25 * (4e-4 + 0.03 ** 2))
    assert mixture_variances(sel, []) == {}


def test_restate_widens_never_narrows_and_keeps_bounds():
    est = {"mu_drum": ParameterEstimate("mu_drum", 0.4, "–", 0.01, (0.38, 0.42), 0.05, 1.5),
           "h": ParameterEstimate("h", 30.0, "W", 2.0, (26.0, 34.0), 29.0, 400.0)}
    fit = SimpleNamespace(data=np.zeros(100), effective_parameters={"torque": 2.0, "temperature": 2.0},
                          names=["mu_drum", "h"], estimates=est)
    restate(fit, {"mu_drum": 0.02 ** 2, "h": 1.0})
    assert est["mu_drum"].stderr == pytest.approx(0.02) and est["mu_drum"].ci95[1] - 0.4 == pytest.approx(
        1.972 * 0.02, rel=1e-3)
    assert est["h"].stderr == 2.0 and est["h"].ci95[0] == 29.0          # narrower refused; clipped at the bound
