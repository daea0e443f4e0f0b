import pytest

from rollaway.hold import hold_margin
from rollaway.hold.scenario import scenario_from_mapping


def make_scenario(**kw):
    base = {"name": "t", "grade_pct": 20, "direction": "downhill", "occupants": 1, "hand_force_N": 400,
            "duration_s": 10, "initial_drum_temp_C": 200}
    return scenario_from_mapping({**base, **kw}, where="test")


def force_for_margin(margin, grade_pct, direction, occupants=1):
    """Hand force giving a constant brake margin at ambient drum temperature (no cooling)."""
    from rollaway.model.parameters import paper
    p = paper()
    t0 = p.ambient_temp_C
    m1, m2 = (float(hold_margin(p, 0.0, f, grade_pct, direction, occupants, initial_temp_C=t0)) for f in (300, 400))
    slope = (m2 - m1) / 100.0
    return 300 + (margin - m1) / slope


@pytest.fixture
def scenario():
    return make_scenario
