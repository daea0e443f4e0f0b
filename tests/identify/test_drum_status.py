"""One brake parameter's status (rollaway.identify.drum_status): its 95 % interval, fitted or held."""
from __future__ import annotations

import pytest

from rollaway.identify.drum_status import ParameterStatus
from rollaway.model.drum_parameters import FREE_PARAMETERS


def test_a_fitted_parameter_keeps_the_fits_interval():
    e = ParameterStatus("mu_drum", "fitted", 0.41, 0.4, "–", 0.02, (0.37, 0.45))
    assert e.interval() == ((0.37, 0.45), "fit")
    assert e.as_dict()["ci95"] == [0.37, 0.45] and e.as_dict()["ci95_from"] == "fit"


@pytest.mark.parametrize("name, value", [("mu_drum", 0.4), ("shoe_arm_ratio", 0.857), ("ambient_temp_C", 27.0)])
def test_a_held_parameter_gets_its_assumed_spread_as_interval(name, value):
    sd = FREE_PARAMETERS[name].spread(value)
    e = ParameterStatus(name, "fixed", value, value, FREE_PARAMETERS[name].unit, prior_sd=sd, reason="not needed")
    (lo, hi), source = e.interval()
    assert source == "assumed spread"
    assert lo == pytest.approx(max(FREE_PARAMETERS[name].lower, value - 1.96 * sd))
    assert hi == pytest.approx(min(FREE_PARAMETERS[name].upper, value + 1.96 * sd))
    assert f"95 % [{lo:.4g}, {hi:.4g}] [assumed]" in e.line()


def test_the_held_interval_stays_inside_the_bounds():
    e = ParameterStatus("gap_m", "fixed", 0.0, 0.0, "m", prior_sd=6e-4, reason="held at the set's value")
    (lo, hi), _ = e.interval()
    assert lo == FREE_PARAMETERS["gap_m"].lower == 0.0 and hi == pytest.approx(1.96 * 6e-4)


def test_a_logged_parameter_without_spread_has_no_interval():
    e = ParameterStatus("ambient_temp_C", "logged", 21.0, 27.0, "°C", reason="read from the log")
    assert e.interval() == (None, None)
    assert e.as_dict()["ci95"] is None and "95 %" not in e.line()
