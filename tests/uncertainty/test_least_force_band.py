"""The least hand force's predictive band (rollaway.uncertainty.draws.least_force_band) against its nominal curve."""
from __future__ import annotations

import numpy as np

from rollaway.hold import minimum_hand_force_N
from rollaway.model.drum_model import Covariance, DrumModel
from rollaway.uncertainty.draws import least_force_band


def test_band_brackets_the_nominal_least_force_and_widens_with_the_model_error():
    cov = Covariance(("mu_drum", "heat_transfer_W_m2K"), np.diag([0.01 ** 2, 2.0 ** 2]))
    model = DrumModel("paper", covariance=cov)
    grades = np.array([10.0, 20.0, 30.0])
    band = least_force_band(model, grades, "uphill", 1, 3600.0, 200.0, draws=60)
    nominal = minimum_hand_force_N(model, grades, "uphill", 1, 3600.0, initial_temp_C=200.0)
    assert np.all(band["p5"] <= nominal + 1e-6) and np.all(nominal <= band["p95"] + 1e-6)
    wide = DrumModel("paper", covariance=cov, predictive={"model_error_rel_sd": 0.05, "model_error_dof": 7})
    band2 = least_force_band(wide, grades, "uphill", 1, 3600.0, 200.0, draws=60)
    assert np.all(band2["p95"] - band2["p5"] > band["p95"] - band["p5"])
