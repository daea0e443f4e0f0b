"""simulate(): fast (event-driven skip) against fixed stepping, and the committed scenarios."""
from pathlib import Path

import pytest

from rollaway.hold.scenario import load_scenario
from rollaway.sim import SimResult, simulate
from tests.sim.conftest import make_scenario

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"


def test_fast_matches_fixed_on_a_cooling_rollaway():
    """200 N at 200 °C facing uphill: the analytic brake margin crosses 1 at ≈ 292 s."""
    s = make_scenario(grade_pct=20, direction="uphill", hand_force_N=200, duration_s=400)
    fast, fixed = simulate(s, mode="fast"), simulate(s, mode="fixed")
    assert fast.outcome == fixed.outcome == "brake_slip"
    assert fast.rollaway_time_s == pytest.approx(fixed.rollaway_time_s, abs=1.0)
    assert fast.rollaway_time_s == pytest.approx(fast.analytic_time_to_slip_s, abs=30.0)
    assert fast.rollaway_time_s > fast.analytic_time_to_slip_s      # the brake slips first, then 5 cm of travel
    assert fast.integrated_time_s < 0.5 * fixed.integrated_time_s
    assert fast.capacity_Nm_at_rollaway < fast.demand_Nm_at_rollaway
    assert fast.min_margin == pytest.approx(fixed.min_margin, rel=1e-3)
    assert fixed.slip_ratio == pytest.approx(0.0, abs=0.05)


def test_one_hour_hold_is_fast_and_integrates_little():
    s = load_scenario(SCENARIOS / "hot-parking-1h.toml")
    r = simulate(s)
    assert r.outcome == "held" and r.rollaway_time_s is None
    assert r.sim_time_s == pytest.approx(3600.0, abs=0.05)
    assert r.integrated_time_s <= 5.0
    assert r.wall_time_s < 3.0            # ≤ 1 s on an idle machine; see benchmarks/bench_simulate.py
    assert r.max_displacement_m < 1e-3
    assert r.min_margin == pytest.approx(1.3863, abs=1e-3)     # analytic margin at 3600 s


def test_fast_mode_does_not_skip_a_sliding_car():
    r = simulate(load_scenario(SCENARIOS / "tyre-skid.toml"))
    assert r.outcome == "tyre_skid"
    assert r.trace.skips == []
    assert r.slip_ratio > 0.9
    assert r.rollaway_time_s < 2.0


@pytest.mark.parametrize("name,expected", [
    ("fmvss135-downhill", "held"), ("fmvss135-uphill", "held"), ("unr13h-laden-downhill", "held"),
    ("unr13h-laden-uphill", "held"), ("grade30-downhill", "tyre_skid"), ("grade30-uphill", "held"),
    ("hot-parking-1h", "held"), ("hot-parking-rollaway", "brake_slip"), ("tyre-skid", "tyre_skid"),
    ("five-occupants", "held")])
def test_committed_scenarios(name, expected):
    r = simulate(load_scenario(SCENARIOS / f"{name}.toml"))
    assert isinstance(r, SimResult)
    assert r.outcome == expected
    d = r.to_dict()
    for key in ("outcome", "rollaway_time_s", "max_displacement_m", "min_margin", "wall_time_s"):
        assert key in d
    assert (d["rollaway_time_s"] is None) == (expected == "held")


def test_bad_mode_is_a_user_error():
    from rollaway.errors import UserError
    with pytest.raises(UserError, match="fast"):
        simulate(make_scenario(), mode="quick")


def test_flat_road_and_released_brake():
    flat = simulate(make_scenario(grade_pct=0, hand_force_N=0, duration_s=5))
    assert flat.outcome == "held" and flat.to_dict()["min_margin"] is None
    released = simulate(make_scenario(hand_force_N=0, duration_s=5))
    assert released.outcome == "brake_slip" and released.min_margin == 0.0
    assert released.capacity_Nm_at_rollaway == 0.0
