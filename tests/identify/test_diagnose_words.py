"""The sentences of a diagnosis that describe the calibrated drum."""
from types import SimpleNamespace

from rollaway.identify.calibrate import ParameterEstimate
from rollaway.identify.diagnose_words import drum_words


def _estimate(name, value, lo, hi, at_bound=""):
    return ParameterEstimate(name, value, "–", 0.01, (value - 0.02, value + 0.02), lo, hi, at_bound)


def test_a_freed_brake_parameter_at_a_bound_of_its_range_is_said_to_be_there():
    """μ_d pushed to its upper bound by a bare drum standing in for a missing effect is marked, the others are
    given as numbers; with nothing freed the sentence says so."""
    fit = SimpleNamespace(values={"mu_drum": 1.0, "shoe_arm_ratio": 0.377},
                          estimates={"mu_drum": _estimate("mu_drum", 1.0, 0.02, 1.0, "upper"),
                                     "shoe_arm_ratio": _estimate("shoe_arm_ratio", 0.377, 0.1, 2.0)})
    words = drum_words(fit, ("mu_drum", "shoe_arm_ratio"))
    assert words.startswith("mu_drum = 1 (its upper bound: the bare drum leans on it")
    assert words.endswith("shoe_arm_ratio = 0.377")
    assert "bound" not in words.split("shoe_arm_ratio")[1]
    assert drum_words(fit, ()) == "nothing freed"
