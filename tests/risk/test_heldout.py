"""Held-out checks: populations the risk code was not written against, truths from tests/risk/heldout_truths.py.

The truths call only the hold package's closed forms, scipy.stats and scipy's roots and quadrature
(no rollaway.risk code); each estimate is checked on several seeds: the interval holds the truth at
its nominal rate, rare rates within 30 %, Sobol total indices within 0.05, designs within 2 N.
"""
import numpy as np
import pytest
from scipy import optimize, stats

from rollaway.errors import UserError
from rollaway.risk.design import design
from rollaway.risk.estimators import estimate
from rollaway.risk.population import population_from_mapping
from rollaway.risk.sensitivity import sobol_indices
from tests.risk.heldout_truths import (BASE, fails_margin, force_threshold, rate_force_and, rate_one,
                                       sobol_total)
from tests.risk.truths import misses_allowed

Z6 = float(stats.norm.isf(1e-6))


def _pop(base, vary, corr=None):
    return population_from_mapping({**base, "vary": vary, **({"correlation": corr} if corr else {})},
                                   where="heldout.toml")


def _coverage(pop, truth, seeds, method="auto", samples=200_000, within=None):
    misses = 0
    for s in seeds:
        e = estimate(pop, method, samples, s)
        lo, hi = e.total.ci95
        misses += not lo <= truth <= hi
        if within is not None:
            assert abs(e.total.probability / truth - 1) < within, (s, e.total, truth)
    assert misses <= misses_allowed(len(seeds)), (misses, truth)
    return e


ONE_INPUT = [   # (fixed values, name, distribution): one varied input, exact rate by roots + the CDF
    ({"hand_force_N": 250, "direction": "both"}, "mu_drum", {"uniform": [0.3, 0.6]}),
    ({"direction": "downhill"}, "hand_force_N", {"lognormal": [300, 0.25]}),
    ({"direction": "both"}, "hand_force_N", {"triangular": [150, 300, 500]}),
    ({"direction": "both"}, "hand_force_N", {"normal": [280, 60], "truncate": [150, 500]}),
    ({"hand_force_N": 300}, "grade_pct", {"normal": [0, 12]}),                   # fails at both ends
    ({"hand_force_N": 300, "direction": "both"}, "grade_pct", {"uniform": [-30, 30]}),
    ({"hand_force_N": 225, "direction": "both"}, "occupants",
     {"choice": [0, 1, 2, 3, 4, 5], "weights": [.3, .3, .2, .1, .05, .05]}),
    ({"hand_force_N": 260, "duration_s": 3600}, "initial_drum_temp_C", {"triangular": [27, 150, 400]}),
    ({"hand_force_N": 270, "duration_s": 1800, "initial_drum_temp_C": 300, "direction": "both"},
     "heat_transfer_W_m2K", {"normal": [40, 15], "truncate": [5, 100]}),
]


@pytest.mark.parametrize("fixed,name,spec", ONE_INPUT, ids=[f"{c[1]}-{next(iter(c[2]))}" for c in ONE_INPUT])
def test_one_varied_input_interval_holds_the_exact_rate(fixed, name, spec):
    base = {**BASE, **fixed}
    truth = rate_one(name, spec, base)
    assert 1e-3 < truth < 0.999
    _coverage(_pop(base, {name: spec}), truth, range(6), within=0.3)


def _grade_sd_for(rate, base):
    return optimize.brentq(lambda s: np.log(max(rate_one("grade_pct", {"normal": [0, s]}, base), 1e-300))
                           - np.log(rate), 3, 12, xtol=1e-6)


def test_one_ppm_with_a_failure_set_in_two_parts_both_directions():
    """Grade N(0, s) facing either way: it fails at both ends; one design point gave half the rate."""
    base = {**BASE, "hand_force_N": 300, "direction": "both"}
    sd = _grade_sd_for(1e-6, base)
    truth = rate_one("grade_pct", {"normal": [0, sd]}, base)
    e = _coverage(_pop(base, {"grade_pct": {"normal": [0, sd]}}), truth, range(8), samples=1_000_000, within=0.3)
    assert e.method == "is"


def test_one_ppm_uniform_mu_with_a_lower_spec_limit_and_a_force_tail():
    """μ_d uniform from a lower spec limit just under the threshold: the rate is exactly 1 ppm; and a
    hand-force normal tail at 1 ppm."""
    mu_star = optimize.brentq(lambda m: float(fails_margin({"mu_drum": m}).ravel()[0]), 0.05, 1.0, xtol=1e-14)
    lower = (mu_star - 1e-6 * 0.6) / (1 - 1e-6)
    _coverage(_pop(BASE, {"mu_drum": {"uniform": [lower, 0.6]}}), 1e-6, range(6), samples=1_000_000, within=0.3)
    f_star = force_threshold({**BASE, "mu_drum": 0.4})
    base = {**BASE, "mu_drum": 0.4}
    _coverage(_pop(base, {"hand_force_N": {"normal": [f_star + Z6 * 35, 35]}}), 1e-6, range(4), samples=1_000_000,
              within=0.3)


@pytest.mark.parametrize("rho", [0.0, -0.5, 0.6])
def test_two_correlated_inputs_rare_rate(rho):
    """μ_d uniform and the hand force normal, Gaussian copula ρ: 5·10⁻⁹ to 2·10⁻⁵ by quadrature."""
    mu, force = {"uniform": [0.33, 0.6]}, {"normal": [420, 40]}
    truth = rate_force_and("mu_drum", mu, force, BASE, rho)
    corr = [{"between": ["mu_drum", "hand_force_N"], "rho": rho}] if rho else None
    _coverage(_pop(BASE, {"mu_drum": mu, "hand_force_N": force}, corr), truth, range(5), samples=1_000_000,
              within=0.3)


def test_no_failure_seen_gives_an_upper_bound_not_zero():
    """A population that never fails here: 0 with an interval that admits what the cars cannot exclude."""
    pop = _pop({**BASE, "direction": "both"}, {"occupants": {"choice": [0, 1, 2, 3, 4, 5]}})
    e = estimate(pop, "is", 100_000, 0)
    assert e.total.probability == 0 and 0 < e.total.ci95[1] < 1e-3


def test_five_inputs_total_indices_match_an_independent_pick_freeze():
    vary = {"mu_drum": {"normal": [0.42, 0.05], "truncate": [0.25, 0.6]}, "hand_force_N": {"uniform": [250, 450]},
            "grade_pct": {"triangular": [8, 18, 30]}, "initial_drum_temp_C": {"lognormal": [150, 0.3]},
            "heat_transfer_W_m2K": {"uniform": [20, 60]}}
    base = {**BASE, "direction": "both", "duration_s": 1800}
    total, _ = sobol_total(vary, base, n=1_000_000)
    pop = _pop(base, vary)
    for seed in (0, 1, 2):
        s = sobol_indices(pop, 2 ** 12, seed)
        for i, name in enumerate(s.names):
            assert abs(s.total[i] - total[name]) < 0.05, (seed, name, s.total[i], total[name])


def test_least_hand_force_for_one_ppm_and_greatest_grade_within_tolerance():
    occ = {"choice": [0, 1, 2, 3, 4, 5], "weights": [.3, .3, .2, .1, .05, .05]}
    base = {**BASE, "direction": "both"}

    def rate(f):
        mu_star = [optimize.brentq(lambda m: float(fails_margin({"mu_drum": m, "hand_force_N": f, "occupants": o},
                                                                 base).ravel()[0]), 0.01, 1.0, xtol=1e-13)
                   for o in occ["choice"]]
        return float(np.dot(occ["weights"], stats.norm.cdf((np.array(mu_star) - 0.42) / 0.04)))
    truth = optimize.brentq(lambda f: np.log(rate(f)) - np.log(1e-6), 250, 400, xtol=1e-9)
    pop = _pop(base, {"mu_drum": {"normal": [0.42, 0.04]}, "occupants": occ})
    for seed in (0, 1):
        d = design(pop, "hand_force_N", 1e-6, 1_000_000, seed)
        assert d.side == "least" and abs(d.value - truth) < 2.0, (seed, d.value, truth)
    base = {**BASE, "hand_force_N": 330, "direction": "both"}
    grade = optimize.brentq(lambda g: rate_one("mu_drum", {"uniform": [0.3, 0.6]}, {**base, "grade_pct": g}) - 1e-3,
                            1, 40, xtol=1e-9)
    d = design(_pop(base, {"mu_drum": {"uniform": [0.3, 0.6]}}), "grade_pct", 1e-3, 1_000_000, 0)
    assert d.side == "greatest" and abs(d.value - grade) < 0.1


BAD = [
    ('mu_drum = { normal = [0.4, 0.3] }', "vary.mu_drum"),
    ('occupants = { uniform = [0, 5] }', "vary.occupants"),
    ('occupants = { choice = [0, 1], weights = [0, 0] }', "vary.occupants.weights"),
    ('hand_force_N = { normal = [400, 35], truncate = [500, 300] }', "vary.hand_force_N.truncate"),
    ('hand_force_N = { normal = [400, 35], uniform = [1, 2] }', "vary.hand_force_N"),
    ('mu_drum = { uniform = [0.3, inf] }', "vary.mu_drum.uniform"),
    ('gap_m = { uniform = [-0.001, 0.001] }', "vary.gap_m"),
    ('mu_drum = { uniform = [0.3, 0.6] }\nhand_force_N = { normal = [400, 35] }\ninitial_drum_temp_C = '
     '{ uniform = [27, 300] }\n[[correlation]]\nbetween = ["mu_drum", "hand_force_N"]\nrho = 0.9\n[[correlation]]\n'
     'between = ["mu_drum", "initial_drum_temp_C"]\nrho = 0.9\n[[correlation]]\nbetween = ["hand_force_N", '
     '"initial_drum_temp_C"]\nrho = -0.9', "correlation"),
]


@pytest.mark.parametrize("text,key", BAD)
def test_held_out_bad_populations_are_one_line_errors(write_population, text, key):
    from rollaway.risk import load_population
    path = write_population("[vary]\n" + text + "\n")
    with pytest.raises(UserError) as err:
        load_population(path)
    msg = str(err.value)
    assert "\n" not in msg and str(path) in msg and f"'{key}" in msg, msg


def test_one_ppm_of_tyre_skids_is_the_tyre_mode():
    """tyre_road_mu normal, a strong brake on 30 %: only the tyres skid, at 1 ppm (the threshold by Brent)."""
    base = {**BASE, "hand_force_N": 500, "mu_drum": 0.5, "direction": "both", "grade_pct": 30}
    mu_star = optimize.brentq(lambda m: float(fails_margin({"tyre_road_mu": m}, base).ravel()[0]), 0.05, 2.0,
                              xtol=1e-14)
    pop = _pop(base, {"tyre_road_mu": {"normal": [mu_star + Z6 * 0.05, 0.05]}})
    e = _coverage(pop, 1e-6, range(6), samples=1_000_000, within=0.3)
    assert e.brake.probability == 0 and abs(e.tyres.probability / 1e-6 - 1) < 0.3


def test_a_negative_seed_is_a_one_line_error():
    pop = _pop(BASE, {"mu_drum": {"uniform": [0.3, 0.6]}})
    with pytest.raises(UserError, match="--seed -5 must be a whole number"):
        estimate(pop, "mc", 1000, -5)
