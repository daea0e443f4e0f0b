"""The vectorised limit state against the hold check car by car; a calibrated model's own scatter joins in."""
import dataclasses

import numpy as np
import pytest
from scipy import optimize, stats

from rollaway.hold import analytic_verdict, min_brake_margin
from rollaway.model.drum_model import Covariance, DrumModel
from rollaway.risk import load_population
from rollaway.risk.estimators import estimate
from rollaway.risk.limit_state import margins

VARY = """[vary]
mu_drum = { uniform = [0.3, 0.6] }
hand_force_N = { normal = [300, 45] }
initial_drum_temp_C = { triangular = [27, 120, 300] }
occupants = { choice = [0, 1, 5] }
grade_pct = { uniform = [5, 35] }
drum_radius_m = { normal = [0.09, 0.003] }
"""


def test_margins_equal_the_hold_check_of_each_car(write_population):
    head = ('grade_pct = 20\ndirection = "both"\noccupants = 5\nhand_force_N = 400\nduration_s = 600\n'
            'initial_drum_temp_C = 200\n')
    pop = load_population(write_population(VARY, head=head))
    v = pop.values_from_normal(np.random.default_rng(0).standard_normal((40, pop.dim)))
    m = margins(pop, v)
    for i in range(40):
        params = pop.base.params.replace(drum_radius_m=float(v["drum_radius_m"][i]))
        verdicts = [analytic_verdict(params, hand_force_N=v["hand_force_N"][i], grade_pct=v["grade_pct"][i],
                                     direction=d, occupants=int(v["occupants"][i]), duration_s=600.0,
                                     initial_temp_C=v["initial_drum_temp_C"][i], mu_drum=v["mu_drum"][i])
                    for d in ("uphill", "downhill")]
        assert m.brake[i] == pytest.approx(min(x.brake_margin_min for x in verdicts), rel=1e-9)
        assert m.tyre[i] == pytest.approx(min(x.tyre_margin for x in verdicts), rel=1e-12)
        assert m.fails[i] == (not all(x.holds for x in verdicts))


def test_a_model_with_effects_matches_the_numeric_hold_check(write_population, tmp_path):
    model = DrumModel("paper", ["lining_creep"], {"lining_creep.relaxed_fraction": 0.15,
                                                  "lining_creep.relaxation_time_s": 900.0})
    path = tmp_path / "creep.toml"
    from rollaway.model.model_file import save_model
    save_model(model, path)
    head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\n'
            'duration_s = 3600\ninitial_drum_temp_C = 200\n')
    pop = load_population(write_population("[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"
                                           "hand_force_N = { normal = [300, 40] }\n", head=head))
    assert pop.model.has_effects
    v = pop.values_from_normal(np.random.default_rng(1).standard_normal((60, pop.dim)))
    got = margins(pop, v).brake
    want = min_brake_margin(pop.model, v["hand_force_N"], 20.0, "uphill", 5, 3600.0, mu_drum=v["mu_drum"])
    near = np.abs(want - 1) < 0.2                # refined by the numeric hold check itself
    assert near.sum() >= 10
    np.testing.assert_allclose(got[near], want[near], rtol=1e-9)
    np.testing.assert_allclose(got, want, rtol=2e-3)   # far from 1: the 41-instant screen


def test_a_calibrated_models_covariance_joins_the_scatter(write_population, tmp_path):
    """Nothing varied, μ_d fitted as N(0.36, 0.02): the rate is P(μ_d < μ*) of that normal (truncated to the
    fitted value's bounds, which lie far out) — an exact truth from root finding."""
    from rollaway.model.model_file import save_model
    model = DrumModel(dataclasses.replace(DrumModel("paper").params, mu_drum=0.36),
                      covariance=Covariance(("mu_drum",), np.array([[0.02 ** 2]])))
    path = tmp_path / "cal.toml"
    save_model(model, path)
    head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 250\n'
            'duration_s = 300\ninitial_drum_temp_C = 200\n')
    pop = load_population(write_population("", head=head))
    mu_star = optimize.brentq(lambda mu: float(min_brake_margin(pop.model.params, 250.0, 20, "uphill", 5, 300.0,
                                                                mu_drum=mu)) - 1, 0.05, 1.0)
    truth = stats.norm.cdf(mu_star, 0.36, 0.02)
    assert 0.05 < truth < 0.95
    misses = 0
    for seed in range(10):
        e = estimate(pop, "mc", 20_000, seed=seed)
        misses += not (e.total.ci95[0] <= truth <= e.total.ci95[1])
    assert misses <= 3


def _catalogue():
    from rollaway.effects import CATALOGUE, get_effect
    return [n for n in sorted(CATALOGUE) if not get_effect(n).per_test_parameters()]


@pytest.mark.parametrize("effect", _catalogue())
def test_every_catalogue_effect_runs_with_a_calibrated_drum_drawn_per_car(effect, write_population, tmp_path):
    """A calibrated model whose fitted brake parameters (μ_d, the shoe-arm ratio) are drawn per car: each car's
    arms reach the effect's hook as arrays (friction_temperature's self-locking bound once took ``max`` of them)."""
    from rollaway.effects import get_effect
    from rollaway.model.model_file import save_model
    eff = get_effect(effect)
    values = {f"{effect}.{k}": v for k, v in eff.typical_values().items()}
    model = DrumModel(dataclasses.replace(DrumModel("paper").params, mu_drum=0.38), [effect], values,
                      covariance=Covariance(("mu_drum", "shoe_arm_ratio"), np.diag([0.01 ** 2, 0.05 ** 2])))
    path = tmp_path / "cal.toml"
    save_model(model, path)
    head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 300\n'
            'duration_s = 600\ninitial_drum_temp_C = 200\n')
    pop = load_population(write_population("[vary]\nhand_force_N = { normal = [300, 30] }\n", head=head))
    e = estimate(pop, "mc", 400, seed=0)
    assert 0.0 <= e.total.ci95[0] <= e.total.probability <= e.total.ci95[1] <= 1.0


def test_a_fleet_below_the_tested_forces_carries_the_benchs_own_force_extrapolation(write_population, tmp_path):
    """As in a single car's band (rollaway.uncertainty.draws.rollaway_risk): below the tested hand forces each car's
    model error is at least the bench's own error of predicting its lowest force from the others, scaled to the
    distance (rollaway.uncertainty.predictive.edge_sd)."""
    from rollaway.model.model_file import save_model
    from rollaway.risk.limit_state import model_draws
    spread = {}
    for edge in (None, [0.05, 0.5]):
        pred = {"model_error_rel_sd": 0.0, "model_error_floor_rel_sd": 0.0, "model_error_dof": 5,
                "tested_hand_force_N": [180.0, 360.0], "tested_initial_temp_C": [100.0, 250.0],
                "tested_duration_s": 3600.0, "tested_directions": ["downhill", "uphill"]}
        if edge:
            pred["model_error_edge_low"] = edge
        model = DrumModel("paper", covariance=Covariance(("mu_drum",), np.array([[1e-6]])), predictive=pred)
        path = tmp_path / f"m{bool(edge)}.toml"
        save_model(model, path)
        head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 135\n'
                'duration_s = 3600\ninitial_drum_temp_C = 200\n')
        pop = load_population(write_population("", head=head))
        spread[bool(edge)] = float(np.std(model_draws(pop, 4000, np.random.default_rng(0))["eps"]))
    assert spread[True] > 20 * spread[False] and spread[True] > 0.05, spread


def test_a_fleet_facing_the_untested_direction_carries_the_torque_over_as_a_single_car_does(write_population, tmp_path):
    """A model calibrated on downhill tests with μ_d = 0.15 (a softer lining's torque scale): cars facing uphill have
    their brake margin carried over by a friction coefficient drawn apart from μ_d
    (rollaway.uncertainty.direction.carry_factor, the same as a single car's band), the median margin lower than with
    μ_d's own direction ratio; cars facing the tested direction are untouched."""
    from rollaway.model.model_file import save_model
    from rollaway.risk.limit_state import model_draws
    from rollaway.uncertainty.direction import carry_factor
    pred = {"model_error_rel_sd": 0.0, "model_error_floor_rel_sd": 0.0, "model_error_dof": 5,
            "tested_hand_force_N": [180.0, 360.0], "tested_initial_temp_C": [100.0, 250.0],
            "tested_duration_s": 3600.0, "tested_directions": ["downhill"]}
    model = DrumModel(dataclasses.replace(DrumModel("paper").params, mu_drum=0.15),
                      covariance=Covariance(("mu_drum",), np.array([[1e-8]])), predictive=pred)
    path = tmp_path / "down.toml"
    save_model(model, path)
    got = {}
    for direction in ("uphill", "downhill"):
        head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "{direction}"\noccupants = 1\n'
                'hand_force_N = 300\nduration_s = 3600\ninitial_drum_temp_C = 200\n')
        pop = load_population(write_population("", head=head))
        draws = model_draws(pop, 2000, np.random.default_rng(0))
        assert "friction_z" in draws
        carried = margins(pop, {}, 2000, draws).brake
        plain = margins(pop, {}, 2000, {k: v for k, v in draws.items() if k != "friction_z"}).brake
        got[direction] = (carried, plain, draws["friction_z"])
    carried, plain, z = got["uphill"]
    p = model.params
    expect = plain * carry_factor(p.mu_drum, p.shoe_arm_normal_m, p.shoe_arm_friction_m, -1.0, z)
    assert carried == pytest.approx(expect, rel=1e-3) and np.median(carried) < 0.9 * np.median(plain)   # μ_d drawn ± 1e-4
    carried, plain, _ = got["downhill"]
    assert np.array_equal(carried, plain)


def test_a_fleet_carries_the_start_error_of_the_hold_as_a_single_car_does(write_population, tmp_path):
    """A record with a start error (rollaway.uncertainty.bands.start_error: 10 % at the first sample, fading by
    300 s): each car's torque at the start of the hold errs by its own draw of it (the same as a single car's band,
    rollaway.uncertainty.predictive.StartError).  From ambient the torque is flat, so a car's least margin is its
    margin times 1 + its start error where that is negative, and untouched where it is positive (after 300 s
    nothing is left of it); without a start error in the record there is none."""
    from rollaway.model.model_file import save_model
    from rollaway.risk.limit_state import model_draws
    pred = {"model_error_rel_sd": 0.0, "model_error_floor_rel_sd": 0.0, "model_error_dof": 5,
            "tested_hand_force_N": [180.0, 360.0], "tested_initial_temp_C": [20.0, 250.0],
            "tested_duration_s": 3600.0, "tested_directions": ["downhill", "uphill"]}
    got = {}
    for start in (None, [0.1, 0.0, 300.0]):
        model = DrumModel("paper", covariance=Covariance(("mu_drum",), np.array([[1e-12]])),
                          predictive=pred if start is None else {**pred, "model_error_start": start})
        path = tmp_path / f"m{start is None}.toml"
        save_model(model, path)
        amb = model.params.ambient_temp_C
        head = (f'params = "{path.name}"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 1\nhand_force_N = 300\n'
                f'duration_s = 1800\ninitial_drum_temp_C = {amb}\n')
        pop = load_population(write_population("", head=head))
        draws = model_draws(pop, 2000, np.random.default_rng(0))
        got[start is None] = (margins(pop, {}, 2000, draws).brake, draws)
    flat, draws = got[True]
    m0 = flat / (1.0 + draws["eps"])                      # the model error ε (a transducer's 0.1 %) divided out
    assert "start" not in draws and np.std(m0) < 1e-4 * np.mean(m0)
    brake, draws = got[False]
    extra = draws["start"][0]
    assert np.std(extra) > 0.05
    assert brake == pytest.approx(np.median(m0) * (1.0 + draws["eps"]) * (1.0 + np.minimum(extra, 0.0)), rel=1e-3)
