"""rollaway.identify.twins: a friction law and a modulus law facing one way, compared with the arm ratio free; a
lining creep and a cable relaxation beside a law whose form is re-formed (on data the model code did not make:
tests/identify/heldout_names.py, tests/uncertainty/band_questions.py)."""
import os
from types import SimpleNamespace

import pytest

from rollaway.identify.diagnose import diagnose
from rollaway.identify.twins import ARM, LOSSES, TWINS, law_twin_rival, loss_twin_rival, twin_rival
from tests.identify.bench_generator import EFFECTS
from tests.identify.heldout_names import campaign, judge
from tests.uncertainty.band_questions import two_effect_data

SLOW = pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="set ROLLAWAY_SLOW=1 (360 campaigns, ~4 min)")


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


@pytest.mark.parametrize("index, named, truth", [
    (389, "cable_relaxation", "lining_creep"),       # quadratic friction beside an exponential lining creep, one way
    (491, "lining_creep", "cable_relaxation"),       # quadratic friction beside an exponential cable relaxation
])
def test_a_loss_a_partner_law_s_form_picked_is_flagged_beside_its_twin(index, named, truth):
    """Two-effect band campaigns whose second law is not written in the catalogue's form: with it the wrong loss
    wins by 14.7 (389) and 302 (491) in BIC, and nothing was flagged.  With that law re-formed the true loss fits as
    well or better and the held-out tests do not prefer the named one: the set with the true loss is named beside
    the verdict, its fit the true loss beside the re-formed law."""
    effects, *_, data, _ = two_effect_data(index)
    assert {EFFECTS[e][1] for e in effects} & set(LOSSES) == {truth}
    d = diagnose(data)
    named_effects = [e["effect"] for e in d.effects]
    assert named in named_effects, d.summary()
    a = next(a for a in d.alternatives if truth in a["effects"])
    assert set(a["effects"]) == {truth} | (set(named_effects) - {named})
    assert "form freed" in a["why"] and a["delta_bic"] < 6.0
    assert any(getattr(e, "name", "").endswith("_shape") for e in a["fit"].model.effects)


def test_a_friction_fade_named_a_modulus_law_beside_another_effect_is_flagged_once_both_laws_are_re_formed():
    """Two-effect band campaign 649: a friction fade above 150 °C beside a radiating drum, both directions.  The
    catalogue's straight friction line bends the downhill/uphill ratio where the data show no change, and the
    modulus law was named beside radiation with nothing about friction flagged; with both laws re-formed beside
    radiation, friction fits better and is named beside the verdict, its fit the re-formed friction law."""
    effects, *_, data, _ = two_effect_data(649)
    assert set(effects) == {"friction_fade_above", "radiation"}
    d = diagnose(data)
    assert [e["effect"] for e in d.effects] == ["modulus_temperature", "radiation_cooling"], d.summary()
    a = next(a for a in d.alternatives if "friction_temperature" in a["effects"])
    assert set(a["effects"]) == {"friction_temperature", "radiation_cooling"} and a["delta_bic"] < 6.0
    assert "both laws re-formed" in a["why"]
    assert any(getattr(e, "name", "") == "friction_temperature_shape" for e in a["fit"].model.effects)


def test_a_true_friction_law_beside_a_cable_gets_no_modulus_twin():
    """Two-effect band campaign 0: a linear friction law (the catalogue's form) beside a cable relaxation, both
    directions: re-formed, the modulus law is far behind (the downhill/uphill ratio tells them apart) and nothing is
    flagged."""
    effects, *_, data, _ = two_effect_data(0)
    d = diagnose(data)
    assert [e["effect"] for e in d.effects] == ["friction_temperature", "cable_relaxation"], d.summary()
    assert not d.alternatives


@pytest.mark.parametrize("rule, kinds", [(loss_twin_rival, ("lining_creep", "cable_relaxation")),
                                         (law_twin_rival, ("friction_temperature", "modulus_temperature"))])
def test_no_twin_where_the_verdict_holds_neither_twin_or_both_or_one_effect(rule, kinds):
    """A verdict with neither of the two twins, with both, or of one effect: *rivalry* comes back as it was."""
    other = [e for e in ("lining_creep", "cable_relaxation", "friction_temperature") if e not in kinds][:1]
    fit = SimpleNamespace(effects=other + ["radiation_cooling"], jacobian=[[1.0]], values={})
    kept = [{"effects": ["x"]}]
    assert rule(None, None, fit, [], {}, 8.0, rivalry=kept) == kept
    fit.effects = list(kinds)
    assert rule(None, None, fit, [], {}, 8.0, rivalry=kept) == kept
    fit.effects = [kinds[0]]
    assert rule(None, None, fit, [], {}, 8.0) == []
    assert LOSSES == {"lining_creep": "cable_relaxation", "cable_relaxation": "lining_creep"}


@SLOW
def test_over_two_effect_campaigns_a_wrong_loss_is_never_named_without_the_true_one_flagged():
    """Two-effect band campaigns 360–719 that hide one loss with time beside another effect (186 of them): the twin
    of the hidden loss is never named with the true loss left unflagged (5 of them before the re-formed law was
    asked: 389, 413, 491, 536, 689), and a true loss named is flagged beside its twin in at most 1 in 10 (13 of 186
    measured, 11 of them by the exchanged sets before: the data cannot tell a fraction of the clamp force from a
    displacement there, which is no false name)."""
    kinds = {k for k, (_, name) in EFFECTS.items() if name in LOSSES}
    wrong, doubted, n = [], 0, 0
    for i in range(360, 720):
        effects, *_, data, _ = two_effect_data(i)
        losses = [EFFECTS[e][1] for e in effects if e in kinds]
        if len(losses) != 1:
            continue
        n += 1
        d = diagnose(data)
        named = {e["effect"] for e in d.effects}
        flagged = {e for a in d.alternatives for e in a["effects"]}
        truth, twin = losses[0], LOSSES[losses[0]]
        if twin in named and truth not in named | flagged:
            wrong.append(i)
        doubted += truth in named and twin in flagged
    assert n >= 150 and not wrong and doubted <= n / 10, (n, wrong, doubted)


def test_a_modulus_law_that_hid_a_friction_fade_carries_the_pair_into_the_bands_without_naming_it():
    """Two-effect band campaign 123: a straight modulus law beside a friction that fades above 110 °C, both
    directions, another drum.  Named `modulus_temperature` (partial); with its own spline alone in the bands the
    band at 450 N from 200 °C, [0.924, 0.978], lay wholly below the truth's least margin 1.011 (confident and
    wrong).  The law beside the friction law re-formed fits 13 BIC better than the law re-formed and predicts held-out
    tests better: it now carries most of the bands' weight, and the band holds the truth.  It is not named (a
    twin's spline also stands for a cable relaxation elsewhere)."""
    from tests.uncertainty.band_questions import answers
    effects, drum, mu, h, one, data, rng = two_effect_data(123)
    d = diagnose(data)
    assert d.verdict == "modulus_temperature" and not d.alternatives
    alts = d.refined.fit_info["alternatives"]
    w = sum(wi for wi, f in alts if len(f.effects) == 2 and f.effects[0] == "modulus_temperature"
            and f.effects[1].startswith("friction_temperature"))
    assert w > 0.5, [(wi, f.effects) for wi, f in alts]
    rows = {r["question"]: r for r in answers(d.model, 123, effects, drum, mu, h, one, rng, 300)}
    assert rows["force_high"]["covered"] and rows["hotter"]["covered"], rows


@pytest.mark.parametrize("misfit", [False, "partial"])
def test_no_twin_pair_where_the_form_fits_or_the_verdict_is_not_one_law(misfit):
    """An exact form (*misfit* False), a verdict of another kind or of two effects, or no spline of its own: no fit."""
    from rollaway.identify.twins import partial_twin_pair
    creep = SimpleNamespace(effects=["lining_creep"], jacobian=[[1.0]], values={})
    law = SimpleNamespace(effects=["friction_temperature"], jacobian=[[1.0]], values={})
    two = SimpleNamespace(effects=["friction_temperature", "lining_creep"], jacobian=[[1.0]], values={})
    for verdict in (creep, two, law):
        assert partial_twin_pair(None, None, verdict, [], misfit) == []
