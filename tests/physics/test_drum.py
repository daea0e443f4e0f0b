import numpy as np
import pytest

from rollaway.model.brake import unenergised_force
from rollaway.model.parameters import paper
from rollaway.physics import drum, vehicle, cooling


def test_eq16a_linearisation_of_model_md():
    p = paper()
    # docs/model.md: at the paper's values F_l0 ≈ 2.4992e8·u6 + 33.99·ΔT
    assert float(unenergised_force(p, 1e-4, 0.0)) == pytest.approx(2.4992e4, rel=1e-4)
    assert float(unenergised_force(p, 0.0, 1.0)) == pytest.approx(33.99, rel=1e-3)


def test_eq16b_reduces_to_16a_at_zero_gap():
    p = paper()
    a = unenergised_force(p, 1e-4, -50.0, 0.0)
    b = unenergised_force(p, 1e-4, -50.0, 1e-12)
    assert b == pytest.approx(a, rel=1e-9)


def test_direction_sign_and_factor():
    assert drum.direction_sign("downhill") == 1 and drum.direction_sign("uphill") == -1
    f = drum.self_energising_factor(0.4, np.array([1.0, -1.0]), 0.07, 0.06)
    np.testing.assert_allclose(f, [0.07 / (0.07 - 0.024), 0.07 / (0.07 + 0.024)])


def test_contact_loss_clamps_to_zero():
    assert drum.normal_force_N(-5.0, 1.3) == 0.0
    assert drum.normal_force_N(-5.0, np.inf) == 0.0


def test_cooling_time_constant_and_limit():
    tau = cooling.cooling_time_constant_s(7100, 586, 7.7e-4, 40, 0.08)
    assert tau == pytest.approx(1001.1, abs=0.1)
    assert cooling.drum_temperature_C(1e7, 200, 27, tau) == pytest.approx(27)


def test_rear_axle_load_sums_with_front_on_the_flat():
    n_r = vehicle.rear_axle_load_N(1000, 0.0, 1.0, wheelbase_m=2.6, cg_behind_front_m=1.1, cg_height_m=0.55)
    assert n_r == pytest.approx(1000 * 9.81 * 1.1 / 2.6)
