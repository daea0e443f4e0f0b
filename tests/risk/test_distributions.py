"""Marginal distributions: the scipy.stats quantiles far into the tails, truncation, weighted choices."""
import numpy as np
import pytest
from scipy import stats

from rollaway.risk.distributions import marginal_from_table


@pytest.mark.parametrize("table, frozen", [
    ({"uniform": [0.3, 0.6]}, stats.uniform(0.3, 0.3)),
    ({"normal": [400, 35]}, stats.norm(400, 35)),
    ({"lognormal": [40, 0.15]}, stats.lognorm(0.15, scale=40)),
    ({"triangular": [27, 120, 300]}, stats.triang((120 - 27) / 273, 27, 273)),
])
def test_marginals_are_the_scipy_distributions_far_into_the_tails(table, frozen):
    m = marginal_from_table("x", table, "f.toml")
    z = np.array([-7.0, -4.0, -1.0, 0.0, 0.5, 3.0, 7.0])
    p_lo, p_hi = stats.norm.cdf(z), stats.norm.sf(z)
    expect = np.where(z < 0, frozen.ppf(p_lo), frozen.isf(p_hi))
    np.testing.assert_allclose(m.from_normal(z), expect, rtol=1e-9)


def test_truncation_and_weights_give_the_conditional_distribution():
    m = marginal_from_table("x", {"normal": [400, 35], "truncate": [300, 480]}, "f.toml")
    x = m.from_normal(np.random.default_rng(0).standard_normal(200_000))
    assert x.min() >= 300 and x.max() <= 480
    ref = stats.truncnorm((300 - 400) / 35, (480 - 400) / 35, 400, 35)
    assert stats.kstest(x, ref.cdf).pvalue > 1e-3
    c = marginal_from_table("occupants", {"choice": [0, 1, 5], "weights": [3, 1, 1]}, "f.toml")
    v = c.from_normal(np.random.default_rng(1).standard_normal(100_000))
    np.testing.assert_allclose([np.mean(v == k) for k in (0, 1, 5)], [0.6, 0.2, 0.2], atol=0.006)


def test_a_moved_distribution_keeps_its_scatter():
    m = marginal_from_table("x", {"normal": [400, 35], "truncate": [300, 480]}, "f.toml")
    s = m.shifted_to(420.0)
    z = np.array([-2.0, 0.0, 1.0])
    np.testing.assert_allclose(s.from_normal(z), m.from_normal(z) + 420.0 - m.median(), rtol=1e-12)
    assert s.median() == pytest.approx(420.0)
    ln = marginal_from_table("x", {"lognormal": [40, 0.15]}, "f.toml").shifted_to(50.0)
    assert ln.median() == pytest.approx(50.0) and ln.args[1] == 0.15
