"""The MuJoCo car feels the drum model's effects: a clamp-force loss rolls it away at the analytic time."""
import dataclasses

import pytest

from rollaway import hold
from rollaway.model.drum_model import DrumModel
from rollaway.hold.scenario import scenario_from_mapping
from rollaway.sim import simulate


@pytest.fixture(scope="module")
def scenarios():
    base = scenario_from_mapping({"name": "creep", "grade_pct": 20, "direction": "downhill", "occupants": 5,
                                  "hand_force_N": 150, "duration_s": 600, "initial_drum_temp_C": 27},
                                 where="test")
    model = DrumModel(base.params, ["lining_creep"], {"lining_creep.relaxed_fraction": 0.4,
                                                      "lining_creep.relaxation_time_s": 120.0})
    return base, dataclasses.replace(base, model=model)


def test_clamp_force_loss_rolls_away_where_the_paper_model_holds(scenarios):
    base, creeping = scenarios
    args = dict(hand_force_N=150, grade_pct=20, direction="downhill", occupants=5, duration_s=600)
    assert hold.analytic_verdict(base.model, **args).holds
    v = hold.analytic_verdict(creeping.model, **args)
    assert v.outcome == "brake_slip" and 10 < v.time_to_slip_s < 600
    held = simulate(base, mode="fast")
    rolled = simulate(creeping, mode="fast")
    assert held.outcome == "held"
    assert rolled.outcome == "brake_slip"
    # onset within one brake update plus the time to travel the roll-away gate; analytic from the same model
    assert rolled.analytic_time_to_slip_s == pytest.approx(v.time_to_slip_s, rel=1e-9)
    assert v.time_to_slip_s - 0.05 <= rolled.rollaway_time_s <= v.time_to_slip_s + 15.0
