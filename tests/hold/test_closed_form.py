"""Analytic hold check: margins, solved slip time and minimum hand force."""
import numpy as np
import pytest

from rollaway import hold, paper
from rollaway.errors import UserError


def test_required_torque_matches_model_md():
    p = paper()
    np.testing.assert_allclose(hold.required_torque(p, [20, 30], 1), [761.86, 1116.28], atol=0.01)


def test_min_hand_force_is_exact_threshold():
    p = paper()
    for d in ("downhill", "uphill"):
        for grade, occ, dur in ((20, 5, 300), (30, 1, 3600), (12, 0, 1800)):
            f = float(hold.minimum_hand_force_N(p, grade, d, occ, dur))
            t = np.linspace(0, dur, 2001)
            at = hold.hold_margin(p, t, f, grade, d, occ)
            assert at.min() == pytest.approx(1.0, abs=1e-9)
            assert hold.hold_margin(p, t, f * 0.999, grade, d, occ).min() < 1.0


def test_time_to_slip_matches_dense_sampling():
    p = paper()
    f = 200.0
    t_slip = float(hold.time_to_slip_s(p, f, 20, "uphill", 1))
    assert 0 < t_slip < 3600
    t = np.linspace(0, 3600, 360001)
    m = hold.hold_margin(p, t, f, 20, "uphill", 1)
    first_below = t[np.argmax(m < 1.0)]
    assert abs(first_below - t_slip) < 0.02
    assert np.isnan(hold.time_to_slip_s(p, 400.0, 20, "uphill", 1))
    assert hold.time_to_slip_s(p, 100.0, 20, "uphill", 1) == 0.0


def test_tyre_margin_direction_and_negative_grade():
    p = paper()
    down = hold.tyre_adhesion_margin(p, 30, "downhill", 1)
    up = hold.tyre_adhesion_margin(p, 30, "uphill", 1)
    assert down < 1.0 < up  # weight moves off the braked rear axle facing downhill
    assert hold.tyre_adhesion_margin(p, -30, "downhill", 1) == pytest.approx(up)
    assert np.isinf(hold.tyre_adhesion_margin(p, 0, "downhill", 1))


def test_hotter_start_loses_more_margin():
    p = paper()
    hot = hold.hold_margin(p, 3600, 250, 20, "uphill", 1, initial_temp_C=300)
    warm = hold.hold_margin(p, 3600, 250, 20, "uphill", 1, initial_temp_C=100)
    assert hot < warm


@pytest.mark.parametrize("grade", [-100, 100.5, float("nan")])
def test_bad_grade(grade):
    with pytest.raises(UserError, match="grade"):
        hold.required_torque(paper(), grade)


def test_bad_occupants():
    with pytest.raises(UserError, match="occupants"):
        hold.required_torque(paper(), 20, 2.5)


def test_effective_slope_folds_negative_grade_into_facing():
    assert hold.effective_slope(-20, "downhill") == (20.0, "uphill")
    assert hold.effective_slope(30, "uphill") == (30.0, "uphill")
    g, facing = hold.effective_slope(np.array([-10.0, 10.0]), np.array(["uphill", "uphill"]))
    assert list(g) == [10.0, 10.0] and list(facing) == ["downhill", "uphill"]
    p = paper()
    assert hold.time_to_slip_s(p, 200.0, -20, "downhill", 1) == pytest.approx(hold.time_to_slip_s(p, 200.0, 20, "uphill", 1))


@pytest.mark.parametrize("t0", [300.0, 27.0, 0.0])
def test_min_brake_margin_equals_dense_sampling(t0):
    p = paper()
    t = np.linspace(0, 1800, 3601)
    dense = hold.hold_margin(p, t, 250, 20, "uphill", 2, initial_temp_C=t0).min()
    assert hold.min_brake_margin(p, 250, 20, "uphill", 2, 1800, initial_temp_C=t0) == pytest.approx(dense, rel=1e-12)
