import numpy as np
import pytest

from rollaway.sim import outcome as oc


def test_crossing_time_interpolates_and_uses_magnitude():
    t = np.array([0.0, 1.0, 2.0, 3.0])
    assert oc.crossing_time(t, np.array([0, 0.02, 0.06, 0.2]), 0.05) == pytest.approx(1.75)
    assert oc.crossing_time(t, np.array([0, -0.02, -0.06, -0.2]), 0.05) == pytest.approx(1.75)
    assert oc.crossing_time(t, np.array([0, 0.01, 0.02, 0.03]), 0.05) is None


@pytest.mark.parametrize("downhill", [True, False])
def test_slip_ratio_rolling_and_locked(downhill):
    x = np.linspace(0.0, 1.0, 11)
    sgn = 1.0 if downhill else -1.0
    rolling = sgn * x / 0.3
    assert oc.slip_ratio(x, rolling, 0.3, downhill, 0) == pytest.approx(0.0)
    assert oc.slip_ratio(x, np.zeros_like(x), 0.3, downhill, 0) == pytest.approx(1.0)
    assert oc.slip_ratio(x, rolling * 0.5, 0.3, downhill, 2) == pytest.approx(0.5)


def test_classify_gates_on_rollaway_first():
    assert oc.classify(False, 1.0) == "held"          # creep with locked wheels is not a skid
    assert oc.classify(True, 0.9) == "tyre_skid"
    assert oc.classify(True, 0.02) == "brake_slip"
