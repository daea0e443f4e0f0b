"""Sobol indices against a large independent estimate (plain numpy pick-freeze on the hold check) and a closed form."""
import numpy as np
from scipy import stats

from rollaway.hold import min_brake_margin
from rollaway.model.parameters import paper
from rollaway.risk import load_population
from rollaway.risk.sensitivity import sensitivity_chart, sobol_indices

FIVE = """[vary]
mu_drum = { uniform = [0.3, 0.6] }
hand_force_N = { normal = [400, 35] }
initial_drum_temp_C = { triangular = [27, 120, 300] }
occupants = { choice = [0, 1, 2, 3, 4, 5], weights = [0.3, 0.4, 0.15, 0.1, 0.03, 0.02] }
heat_transfer_W_m2K = { lognormal = [40, 0.15] }
"""


def _margin(x):
    """Least brake margin of the five-input population, written out with the hold check alone."""
    import dataclasses
    p = dataclasses.replace(paper(), heat_transfer_W_m2K=x[:, 4])
    return min_brake_margin(p, x[:, 1], 20.0, "uphill", x[:, 3], 300.0, mu_drum=x[:, 0], initial_temp_C=x[:, 2])


def _draw(rng, n):
    occ = rng.choice([0, 1, 2, 3, 4, 5], size=n, p=[0.3, 0.4, 0.15, 0.1, 0.03, 0.02])
    return np.column_stack([rng.uniform(0.3, 0.6, n), rng.normal(400, 35, n),
                            stats.triang((120 - 27) / 273, 27, 273).rvs(n, random_state=rng), occ,
                            40 * np.exp(0.15 * rng.standard_normal(n))])


def independent_total_indices(n=400_000, seed=123):
    """Jansen's total index from independent pick-freeze matrices (numpy only, no SALib)."""
    rng = np.random.default_rng(seed)
    a, b = _draw(rng, n), _draw(rng, n)
    fa, fb = _margin(a), _margin(b)
    var = np.var(np.r_[fa, fb])
    out = []
    for i in range(5):
        ab = a.copy()
        ab[:, i] = b[:, i]
        out.append(np.mean((fa - _margin(ab)) ** 2) / (2 * var))
    return np.array(out)


def test_total_indices_match_a_large_independent_estimate(write_population, tmp_path):
    pop = load_population(write_population(FIVE))
    truth = independent_total_indices()
    for seed in (0, 1):
        s = sobol_indices(pop, 2 ** 13, seed=seed)
        assert s.names == pop.names
        np.testing.assert_allclose(s.total, truth, atol=0.05)
        assert np.all(s.first <= s.total + 0.03) and abs(s.first.sum() - 1) < 0.1   # nearly additive here
        assert s.ranked()[0] == "mu_drum"
    png = sensitivity_chart(s, tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 5000 and png.endswith("s.png")


def test_an_input_without_influence_has_zero_indices_and_one_alone_has_all(write_population):
    """Closed form: with μ_d the only input that moves the margin, S_μ = ST_μ = 1 and the cooled area's ≈ 0
    (the drum is at ambient: no cooling, so cooled_area_m2 cannot act)."""
    head = ('grade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\nduration_s = 300\n'
            'initial_drum_temp_C = 27\n')
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"
                                           "cooled_area_m2 = { uniform = [0.05, 0.1] }\n", head=head))
    s = sobol_indices(pop, 2 ** 12, seed=4).as_dict()
    assert abs(s["mu_drum"]["total"] - 1) < 0.02 and abs(s["mu_drum"]["first"] - 1) < 0.05
    assert abs(s["cooled_area_m2"]["total"]) < 1e-9
    lo, hi = s["mu_drum"]["total_ci95"]
    assert lo <= s["mu_drum"]["total"] <= hi


def test_the_same_seed_gives_the_same_intervals(write_population):
    """Seed 0 included (SALib takes a false seed for none and draws its bootstrap unseeded)."""
    pop = load_population(write_population(FIVE))
    for seed in (0, 3):
        a, b = (sobol_indices(pop, 2 ** 10, seed=seed) for _ in range(2))
        np.testing.assert_array_equal(a.total_ci, b.total_ci)
        np.testing.assert_array_equal(a.first_ci, b.first_ci)
