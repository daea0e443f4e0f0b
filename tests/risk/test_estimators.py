"""Rates against truths computed without rollaway.risk: root finding and quadrature on the hold check.

Several seeds each; the 95 % intervals must hold the truth at about their nominal rate."""
from rollaway.risk import load_population
from rollaway.risk.estimators import estimate
from tests.risk.truths import misses_allowed, rate_mu_uniform


def test_one_uniform_input_mc_intervals_cover_the_measure_below_the_threshold(write_population):
    """μ_d uniform on [0.3, 0.6], 250 N: the rate is the share of [0.3, 0.6] below the root μ*."""
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n").parent / "pop.toml")
    pop = pop.with_fixed("hand_force_N", 250.0)
    truth = rate_mu_uniform(0.3, 0.6, 250.0)
    assert 0.05 < truth < 0.5
    seeds = range(30)
    misses = 0
    for s in seeds:
        e = estimate(pop, "mc", 4000, seed=s)
        assert e.method == "mc" and e.samples == 4000
        misses += not (e.total.ci95[0] <= truth <= e.total.ci95[1])
        assert e.brake.probability == e.total.probability and e.tyres.probability == 0.0   # tyres hold here
    assert misses <= misses_allowed(len(seeds)), misses


def test_tyre_skids_are_a_failure_mode_of_their_own(write_population):
    """A slippery road (μ_r uniform 0.3–1.0) on 30 %: the tyres skid where μ_r·N_r < m g sin θ, found by root."""
    from scipy import optimize

    from rollaway.hold import tyre_adhesion_margin
    from rollaway.model.parameters import paper
    head = ('grade_pct = 30\ndirection = "downhill"\noccupants = 1\nhand_force_N = 500\nduration_s = 300\n'
            'initial_drum_temp_C = 200\n')
    pop = load_population(write_population("[vary]\ntyre_road_mu = { uniform = [0.3, 1.0] }\n", head=head))
    mu_star = optimize.brentq(lambda m: float(tyre_adhesion_margin(paper().replace(tyre_road_mu=m), 30, "downhill", 1))
                              - 1, 0.01, 2.0)
    truth = (mu_star - 0.3) / 0.7
    e = estimate(pop, "mc", 20_000, seed=2)
    assert e.tyres.ci95[0] <= truth <= e.tyres.ci95[1] and e.brake.probability < e.tyres.probability


def test_both_directions_fail_more_often_than_either(write_population):
    text = "[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"
    up = load_population(write_population(text)).with_fixed("hand_force_N", 250.0)
    both = load_population(write_population(text, head=(
        'grade_pct = 20\ndirection = "both"\noccupants = 5\nhand_force_N = 250\nduration_s = 300\n'
        'initial_drum_temp_C = 200\n'), name="both.toml"))
    down = both.with_fixed("grade_pct", 20.0)
    import dataclasses
    down = dataclasses.replace(down, directions=("downhill",))
    r = {k: estimate(p, "mc", 20_000, seed=4).total.probability for k, p in (("up", up), ("down", down), ("both", both))}
    assert r["both"] >= max(r["up"], r["down"]) and r["both"] > 0


def test_same_seed_same_answer_and_chunks_add_up(write_population):
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n")).with_fixed(
        "hand_force_N", 250.0)
    a, b = estimate(pop, "mc", 600_000, seed=9), estimate(pop, "mc", 600_000, seed=9)
    assert a.total == b.total and a.samples == 600_000    # three chunks streamed


def test_nothing_varied_is_plain_monte_carlo_whatever_the_method(write_population):
    pop = load_population(write_population("")).with_fixed("hand_force_N", 200.0)
    for method in ("is", "subset", "form", "auto"):
        e = estimate(pop, method, 1000, seed=0)
        assert e.method == "mc" and e.total.probability == 1.0      # 200 N cannot hold this car
