"""The design that meets a target, against the closed-form least hand force at the target's μ_d quantile."""
import numpy as np
import pytest

from rollaway.errors import UserError
from rollaway.hold import minimum_hand_force_N
from rollaway.model.parameters import paper
from rollaway.risk import load_population
from rollaway.risk.design import design, design_chart
from tests.risk.truths import CASE


@pytest.mark.parametrize("target", [0.05, 2e-3])
def test_least_hand_force_within_2_N_of_the_closed_form(write_population, target):
    """μ_d uniform on [0.3, 0.6]: rate ≤ P ⇔ the car at μ_d = 0.3 + 0.3·P holds, so the least force is the
    hold check's least hand force at that μ_d (closed form, eqs. 16, 24)."""
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"))
    truth = float(minimum_hand_force_N(paper(), CASE["grade_pct"], CASE["direction"], CASE["occupants"],
                                       CASE["duration_s"], mu_drum=0.3 + 0.3 * target, initial_temp_C=200.0))
    for seed in (0, 1):
        d = design(pop, "hand_force_N", target, samples=400_000, seed=seed)
        assert d.side == "least" and abs(d.value - truth) < 2.0, (d.value, truth)
        assert d.probability <= target and d.method.startswith("mc")
        v = np.array([c[0] for c in d.curve])
        p = np.array([c[1] for c in d.curve])
        assert np.all(np.diff(v) > 0) and np.all(np.diff(p) <= 0)        # more force, fewer roll-aways


def test_rare_target_by_importance_sampling_and_a_spec_limit(write_population, tmp_path):
    pop = load_population(write_population("[vary]\nmu_drum = { normal = [0.45, 0.037] }\n"
                                           "hand_force_N = { normal = [400, 37] }\n"))
    d = design(pop, "grade_pct", 1e-6, samples=200_000, seed=0)
    assert d.side == "greatest" and d.method.startswith("is") and 10 < d.value < 20
    spec = design(load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n")).with_fixed(
        "hand_force_N", 250.0), "mu_drum.lower", 0.01, samples=200_000, seed=0)
    from tests.risk.truths import mu_threshold
    # truncated at L the μ_d are uniform on [L, 0.6]: rate (μ* − L)/(0.6 − L) = 0.01 gives L in closed form
    truth = (mu_threshold(250.0) - 0.01 * 0.6) / 0.99
    assert spec.side == "least" and abs(spec.value - truth) < 1e-3 and spec.probability <= 0.01
    design_chart(spec, tmp_path / "d.png")
    assert (tmp_path / "d.png").stat().st_size > 5000


def test_design_errors_are_one_line(write_population):
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"))
    for name, target, words in [("hand_force", 1e-3, "hand_force_N"),
                                ("hand_force_N", 2.0, "between 0 and 1"), ("mu_drum.middle", 1e-3, "NAME.lower")]:
        with pytest.raises(UserError, match=words):
            design(pop, name, target, samples=10_000)


def test_a_varied_input_is_designed_by_its_nominal_value(write_population):
    """μ_d ~ uniform [m − 0.15, m + 0.15]: the rate is (μ* − m + 0.15)/0.3 ≤ P, so m = μ* + 0.15 − 0.3·P."""
    from tests.risk.truths import mu_threshold
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n")).with_fixed(
        "hand_force_N", 250.0)
    d = design(pop, "mu_drum", 0.02, samples=200_000, seed=0)
    assert d.side == "least" and abs(d.value - (mu_threshold(250.0) + 0.15 - 0.3 * 0.02)) < 1e-3


def test_occupants_are_designed_in_whole_numbers(write_population):
    """The number of occupants is searched over 0–5, never a fraction: the greatest load whose rate meets the target,
    each whole number's rate on the curve, and the rate grows with the load (more weight, more torque needed)."""
    head = ('grade_pct = 30\ndirection = "uphill"\noccupants = 5\nhand_force_N = 360\nduration_s = 300\n'
            'initial_drum_temp_C = 200\n')
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.2, 0.5] }\n", head=head))
    d = design(pop, "occupants", 0.2, samples=20_000)
    assert d.side == "greatest" and d.value == int(d.value) and 0 <= d.value <= 5
    assert [v for v, _ in d.curve] == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
    rates = [p for _, p in d.curve]
    assert rates == sorted(rates) and rates[0] < rates[-1] and d.probability <= 0.2
    assert 0 < d.value < 5 and rates[int(d.value) + 1] > 0.2


def test_a_design_on_a_population_that_varies_nothing_says_so(write_population):
    pop = load_population(write_population(""))
    with pytest.raises(UserError, match="varies nothing"):
        design(pop, "hand_force_N", 1e-5, samples=10_000)
