"""rollaway.identify.twins: a friction law and a modulus law facing one way, compared with the arm ratio free (on
data the model code did not make: tests/identify/heldout_names.py)."""
from types import SimpleNamespace

from rollaway.identify.diagnose import diagnose
from rollaway.identify.twins import ARM, TWINS, twin_rival
from tests.identify.heldout_names import campaign, judge


def test_a_modulus_law_named_friction_on_one_direction_is_flagged_once_the_arm_ratio_is_free():
    """Held-out names 389: a linear modulus law on two uphill tests of another drum.  With the arm ratio held at the
    set's value friction wins by 13.5 BIC and was named with nothing flagged; with it free in both the two laws are
    within the indistinguishable band and the held-out tests do not prefer friction: the modulus law is named beside
    it, with the other direction as the test that would tell them apart."""
    hidden, data = campaign(389)
    assert hidden == "modulus_linear"
    d = diagnose(data)
    assert d.verdict == "friction_temperature" and judge(hidden, d)["right_or_alternative"], d.summary()
    a = next(a for a in d.alternatives if a["effects"] == ["modulus_temperature"])
    assert "arm ratio" in a["why"] and "downhill" in a["tell_apart"]["words"]
    assert abs(a["delta_bic"]) < 6.0


def test_no_twin_where_the_arm_ratio_was_tested_or_free_or_the_verdict_is_another_law():
    """Both directions tested, the arm ratio already free, or a verdict that is neither law: no refit, no rival."""
    fit = SimpleNamespace(effects=["friction_temperature"], jacobian=[[1.0]], values={})
    one, both = {"directions": ["uphill"]}, {"directions": ["downhill", "uphill"]}
    held = SimpleNamespace(free=("mu_drum",), params=None)
    assert twin_rival(None, held, fit, both, 8.0) is None
    assert twin_rival(None, SimpleNamespace(free=("mu_drum", ARM), params=None), fit, one, 8.0) is None
    other = SimpleNamespace(effects=["lining_creep"], jacobian=[[1.0]], values={})
    assert twin_rival(None, held, other, one, 8.0) is None
    assert TWINS == {"friction_temperature": "modulus_temperature", "modulus_temperature": "friction_temperature"}
