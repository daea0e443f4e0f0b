"""The test that would separate two fitted models (rollaway.identify.separating_test)."""
from types import SimpleNamespace

import pytest

from rollaway.identify.separating_test import FACTORS, FORCE_REACH, tell_apart
from rollaway.model.drum_model import DrumModel
from rollaway.model.parameters import paper

VALIDITY = {"hand_force_N": (200.0, 300.0), "initial_temp_C": (100.0, 200.0), "duration_s": 1800.0,
            "directions": ("downhill",)}


def _fit(**changes):
    """A stand-in for a fit: its model gives this drum (the paper's with *changes*) at any values."""
    drum = DrumModel(paper().replace(**changes))
    return SimpleNamespace(values={}, model=SimpleNamespace(drum_model=lambda values: drum))


def test_two_equal_models_have_nothing_between_them():
    out = tell_apart(_fit(), _fit(), VALIDITY, noise_torque_Nm=5.0)
    assert out["difference_Nm"] == 0.0 and out["tested_difference_Nm"] == 0.0 and out["noise_sigmas"] == 0.0


@pytest.mark.parametrize("noise", [2.0, 20.0])
def test_the_proposed_test_differs_most_and_is_scaled_by_the_torque_noise(noise):
    """A friction coefficient 5 % apart: the torques differ most at the highest force reached, beyond the tested
    range (the two were not fitted to the same data, so they differ within the tested conditions too, but less)."""
    out = tell_apart(_fit(mu_drum=0.40), _fit(mu_drum=0.42), VALIDITY, noise_torque_Nm=noise)
    assert out["difference_Nm"] >= out["tested_difference_Nm"] > 0.0
    assert out["noise_sigmas"] == pytest.approx(out["difference_Nm"] / noise)
    assert out["test"]["hand_force_N"] == pytest.approx(300.0 + FORCE_REACH * 100.0, abs=0.1)
    assert out["factor"] in FACTORS and out["words"].startswith(f"a test facing {out['test']['direction']} at")
    assert max(out["by_factor_Nm"].values()) == out["by_factor_Nm"][out["factor"]]
