"""rollaway.identify.partner (a second effect only on its own evidence: beyond_reform, own_evidence,
beside_reformed), on data the model code did not make (tests/identify/bench_generator.py, tests/identify/heldout_names.py)."""
import os

import numpy as np
import pytest

from rollaway.identify.diagnose import diagnose
from tests.identify.bench_generator import OTHER_DRUMS, generate
from tests.identify.heldout_names import run, summary

SLOW = pytest.mark.skipif(not os.environ.get("ROLLAWAY_SLOW"), reason="set ROLLAWAY_SLOW=1 (48 campaigns, ~5 min)")


def test_a_mis_formed_first_effect_gets_no_partner():
    """A glass-transition (sigmoid) modulus drop: modulus_temperature is its physics in the wrong form; lining_creep
    (in an earlier release lining_creep) lowers BIC and held-out error beside it, but a re-formed modulus_temperature
    predicts held-out tests as well."""
    d = diagnose(generate(["modulus_sigmoid"], sampling="5min", seed=12))
    assert [e["effect"] for e in d.effects] == ["modulus_temperature"], d.summary()
    assert d.remaining_structure and d.effects[0]["form"] == "partial"
    step = next(s for s in d.steps if s.get("step") == "own evidence")
    assert not step["kept"] and step["effect"] != "modulus_temperature" and not step["beyond_reform"]["passes"]
    assert step["beyond_reform"]["heldout_elpd"] < 0
    assert any("not beyond modulus_temperature re-formed" in w for w in d.evidence)


@pytest.mark.parametrize("pair,seed", [(("creep_exponential", "friction_linear"), 33),
                                       (("cable_exponential", "modulus_linear"), 2001)])
def test_a_true_second_effect_beats_the_re_formed_first(pair, seed):
    d = diagnose(generate(pair, sampling="5min", seed=seed))
    assert len(d.effects) == 2 and not d.remaining_structure, d.summary()
    step = next(s for s in d.steps if s.get("step") == "own evidence")
    assert step["kept"] and step["beyond_reform"]["passes"] and 2 * step["beyond_reform"]["better_tests"] > step["beyond_reform"]["tests"]


def test_few_partner_effects_on_a_handful_of_held_out_campaigns():
    s = summary(run(6, start=18))          # friction fade, friction linear, exact and other forms, other drums
    assert s["partner"] <= 1 and s["right_or_alternative"] >= 3, s   # 0.69 right over 48 (docs/identification.md)


@SLOW
def test_partners_and_names_on_48_held_out_campaigns():
    s = summary(run(48))
    assert s["partner"] <= 2 and s["right_or_alternative"] >= 35, s     # 1 and 36 measured (was 3 and 34)


@SLOW
def test_partners_and_names_when_every_kind_meets_every_setting():
    """heldout_names.rotated_campaign: each hidden kind at 1- and 5-min sampling, both directions and one, on drums
    of OTHER_DRUMS and MORE_DRUMS (in :func:`run` a kind always meets the same setting).  Measured: no partner, 43
    of these 48 and 127 of 144 right or flagged; the misses are "none" at the detection limit (radiation at 5-min, creep facing
    one way), which the verdict line names as effects these data could miss."""
    s = summary(run(48, rotated=True))
    assert s["partner"] <= 1 and s["right_or_alternative"] >= 38, s


def test_a_partner_standing_in_for_another_lining_is_not_named():
    """A thicker, softer lining than the paper's (a departure of the drum, one hidden effect): the exact
    friction_temperature is named; a gap or a radial contraction that only stands in for the lining once the brake
    parameters the bare drum held are freed is not (before the rule: 7 of these 8 seeds named one)."""
    partners = 0
    for seed in range(50, 58):
        d = diagnose(generate(["friction_linear"], sampling="5min", seed=seed, drum=OTHER_DRUMS["thick_soft_lining"]))
        assert d.verdict == "friction_temperature", d.summary()
        partners += len(d.effects) > 1
    assert partners <= 2


def test_a_creep_standing_in_for_a_thicker_softer_lining_is_not_named():
    """A sigmoid modulus drop on a thicker, softer lining than the paper's, two hand forces, 5-min samples, 20 seeds:
    the lining's balance of thermal terms (eq. 16) is a departure of the drum that a lining creep of 40 % can
    imitate beside the linear modulus law.  With the gap — a thicker lining in eq. (16b), held because the logs
    cannot tell it from μ_d — freed in both fits the partner test compares, no second effect is named (before: one
    of these seeds named lining_creep beside modulus_temperature; held-out campaign 225 too)."""
    partners = []
    for seed in range(800, 820):
        d = diagnose(generate(["modulus_sigmoid"], sampling="5min", seed=seed, drum=OTHER_DRUMS["thick_soft_lining"],
                              forces=np.linspace(190.0, 360.0, 2), mu=0.35))
        if len(d.effects) > 1:
            partners.append((seed, [e["effect"] for e in d.effects]))
    assert not partners, partners


def test_a_partner_standing_in_for_an_unidentified_eq24_offset_is_not_named():
    """A linear modulus law on a drum with its own eq. (24) law, tested facing uphill only at 3–4 forces: the bare
    drum cannot tell the eq. (24) offset from μ_d and fixes it at the set's value; a radial contraction or a cable
    relaxation then stands in for the offset beside modulus_temperature.  With the offset freed in both fits the
    partner test compares, none is named, and the one-effect model frees the offset it needs (before: 3 of these
    16 seeds named a second effect; held-out campaigns 401 and 569 too).  One may still be: on seed 940 a stiffness
    law beside the modulus sits at the edge of the temperature channel's held-out check (−1.49 against a limit of
    −1.39 or −2.2, depending on refitted folds that floating-point rounding moves): named once in a full test run,
    in none of 4 runs of this test alone."""
    partners, freed = [], 0
    for seed in range(926, 942):
        rng = np.random.default_rng(seed)
        lo = rng.uniform(150.0, 220.0)
        forces = np.linspace(lo, lo + rng.uniform(120.0, 200.0), int(rng.integers(3, 5)))
        d = diagnose(generate(["modulus_linear"], sampling="5min", seed=seed, drum=OTHER_DRUMS["eq24_own"],
                              directions=("uphill",), h=rng.uniform(30.0, 42.0), forces=forces,
                              mu=rng.uniform(0.3, 0.45)))
        assert {"modulus_temperature", "friction_temperature"} & ({d.verdict} | {e for a in d.alternatives
                                                                              for e in a["effects"]}), d.summary()
        if len(d.effects) > 1:
            partners.append((seed, [e["effect"] for e in d.effects]))
        step = next((s for s in d.steps if s.get("step") == "own evidence"), None)
        freed += bool(step and step["beyond_reform"].get("departures") and d.drum.entries["u6_offset_m"].status
                      == "fitted")
    assert len(partners) <= 1, partners
    assert freed >= 2


def test_the_first_of_two_is_the_one_that_explains_more_with_the_drum_they_share():
    """Held-out campaign 46 (a power-law lining creep on a drum with its own eq. (24) law, 1-min): step 1 picks a
    cable relaxation with the bare drum's free set; once the drum frees its eq. (24) offset, the lining creep alone
    explains far more (BIC lower by ~180).  The pair is ordered by that before the partner test, and the
    single-effect rivals are refitted with the same drum: the verdict is the lining creep (before: the cable
    relaxation, no alternative)."""
    from tests.identify.heldout_names import campaign
    _, data = campaign(46)
    d = diagnose(data)
    named = {d.verdict.split(":")[0].split(" ")[0]} | {e for a in d.alternatives for e in a["effects"]}
    assert "lining_creep" in named, d.verdict
    order = [s for s in d.steps if s.get("step") == "order"]
    assert order and order[0]["first"] == "lining_creep"


def test_a_second_effect_is_sought_beside_the_first_re_formed():
    """Friction quadratic in temperature and an exponential lining creep on a drum with its own eq. (24) law
    (1-min, 8 tests; the setting of a two-effect band campaign): beside the catalogue's linear friction the
    forward step picks a cable relaxation, which is no better than the friction re-formed, and the friction
    re-formed alone leaves structure.  Screened beside the re-formed friction, the lining creep passes: both are
    named (before: "none: structure remains")."""
    rng = np.random.default_rng(6637)
    effects = list(rng.choice(["friction_linear", "creep_exponential", "cable_exponential", "gap", "modulus_linear",
                               "radiation", "friction_quadratic", "friction_fade_above", "modulus_sigmoid",
                               "creep_power_law", "cable_log"], 2, replace=False))
    assert effects == ["friction_quadratic", "creep_exponential"]
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drum = list(OTHER_DRUMS.values())[rng.integers(len(OTHER_DRUMS))]
    d = diagnose(generate(effects, sampling="1min", seed=6637, mu=mu, h=h, drum=drum,
                          forces=np.linspace(180.0, 360.0, 4), t0_range=(100.0, 250.0)))
    assert {e["effect"] for e in d.effects} == {"friction_temperature", "lining_creep"}, d.verdict
    assert any(s.get("step") == "beside the re-formed first" for s in d.steps)


def test_one_mis_formed_effect_is_not_a_pair():
    """A sigmoid drop of the lining modulus on another drum (1-min; campaign 9 of
    tests/uncertainty/band_questions.py): friction comes first and, re-formed, still leaves structure; beside it the
    catalogue's modulus law passes — but the modulus law re-formed explains as much alone, so the pair is one
    mis-formed effect and its stand-in.  Before that check it was named friction + modulus (a partner), and the
    band at 280 °C said the car slides where it holds (0.44–0.87 against 1.09)."""
    from tests.uncertainty.band_questions import HIDDEN
    i = 9
    rng = np.random.default_rng(7700 + i)
    hidden = HIDDEN[i % len(HIDDEN)]
    assert hidden == "modulus_sigmoid"
    mu, h = rng.uniform(0.3, 0.45), rng.uniform(25.0, 45.0)
    drum = list(OTHER_DRUMS.values())[rng.integers(len(OTHER_DRUMS))]
    d = diagnose(generate([hidden], sampling="1min", seed=7700 + i, mu=mu, h=h, drum=drum,
                          forces=np.linspace(180.0, 360.0, 4), t0_range=(100.0, 250.0)))
    assert len(d.effects) <= 1, d.verdict


def test_a_zero_offset_per_test_is_judged_within_the_tests():
    """A per-test zero offset refits the held-out test's own level, so beside a mis-formed first effect it always
    "predicts" held-out tests better: held-out campaign 209 (a linear modulus drop, 2 tests, 26 rows) came out
    friction_temperature + torque_zero_offset.  Compared within the tests it has no evidence of its own; a true
    zero offset beside a friction change still has."""
    from tests.identify.heldout_names import campaign
    d = diagnose(campaign(209)[1])
    assert [e["effect"] for e in d.effects] == [d.verdict], d.summary()
    step = next(s for s in d.steps if s.get("step") == "own evidence")
    assert step["effect"] == "torque_zero_offset" and not step["kept"]
    for seed in (1, 6):
        d = diagnose(generate(["zero_offset", "friction_linear"], sampling="5min", seed=seed))
        assert sorted(e["effect"] for e in d.effects) == ["friction_temperature", "torque_zero_offset"], d.summary()


def test_a_first_effect_that_only_shapes_the_second_is_dropped():
    """Held-out campaign 274: a lining creep as a power of time (t^0.35, four tests, 1-min).  Friction falling with
    the temperature came first (it follows the cooling, and the catalogue's exponential creep flattens too early);
    creep then passed its own evidence beside friction re-formed — but friction does not beside creep re-formed (a
    spline in time): it only gave the exponential creep the shape it lacks.  Lining creep is named alone; the pair
    was a partner (the first effect shaping the second)."""
    from tests.identify.heldout_names import campaign, judge
    hidden, data = campaign(274)
    assert hidden == "creep_power_law"
    d = diagnose(data)
    got = judge(hidden, d)
    assert got["right"] and not got["partner"], d.summary()
    step = next(s for s in d.steps if s.get("step") == "own evidence of the first")
    assert step["effect"] == "friction_temperature" and not step["kept"] and not step["beyond_reform"]["passes"]
    assert step["beyond_reform"]["reform_effect"] == "lining_creep_shape"


@pytest.mark.parametrize("pair,seed", [(("creep_exponential", "friction_linear"), 33),
                                       (("cable_exponential", "modulus_linear"), 2001)])
def test_a_true_pair_keeps_both_in_the_reverse_test_too(pair, seed):
    """Each effect of a true pair predicts held-out tests better than the other re-formed: no reverse drop."""
    d = diagnose(generate(pair, sampling="5min", seed=seed))
    assert len(d.effects) == 2
    assert not any(s.get("step") == "own evidence of the first" for s in d.steps), d.steps


@pytest.mark.parametrize("source,index", [("names", 309), ("two", 62)])
def test_a_spline_re_form_on_few_tests_is_judged_by_refitting_the_folds(source, index):
    """A sigmoid modulus drop on three or four tests (held-out campaign 309; two-effect campaign 62, a sigmoid and a
    linear modulus change): friction_temperature beside modulus_temperature beat the modulus spline on held-out tests
    only through the linearised leave-one-test-out, whose step along the spline's directions that one test alone
    informs is huge (a held-out χ² of 56 500 against 855 refitted).  Refitted folds: no partner.  (The modulus
    spline of campaign 309 now settles where the linearised comparison already fails: the same verdict.)"""
    if source == "names":
        from tests.identify.heldout_names import campaign
        hidden, data = campaign(index)
        hidden = [hidden]
    else:
        from tests.uncertainty.band_questions import two_effect_data
        hidden, *_, data, _ = two_effect_data(index)
    assert set(hidden) <= {"modulus_sigmoid", "modulus_linear"} and data.n_tests <= 4
    d = diagnose(data)
    assert [e["effect"] for e in d.effects] == ["modulus_temperature"], d.summary()
    step = next(s for s in d.steps if s.get("step") == "own evidence")
    assert step["effect"] == "friction_temperature" and not step["kept"]
    judged = step["beyond_reform"]
    if judged["heldout"] == "linearised":     # the spline settled where its linear steps hold: no refit needed
        assert source == "names" and not judged["passes"]
        return
    assert judged["heldout"] == "refitted" and judged["refitted_folds"][0] >= 1      # the spline's folds
    assert judged["linearised"]["heldout_elpd"] > judged["heldout_elpd"]
    assert any("refitted where a linear step failed its check" in w for w in d.evidence)


def test_the_screens_beside_a_re_formed_first_hold_its_spline():
    """The screen fits the candidate's and the brake parameters only; the spline stays where the re-formed first put
    it (its BIC ranks the candidates against the same spline; the best is refitted with everything free)."""
    from rollaway.effects import get_effect
    from rollaway.identify.model import DrumPlan
    from rollaway.identify.partner import _all_but
    from rollaway.identify.shape import flexible_effect
    flex = flexible_effect(get_effect("lining_creep"), np.linspace(0.0, 3600.0, 61))
    plan = DrumPlan(None, ("mu_drum", "u6_slope_m_per_N", "heat_transfer_W_m2K"))
    free = _all_but(plan, flex, "friction_temperature")
    assert not any(n.startswith(flex.name + ".") for n in free)
    assert {"mu_drum", "u6_slope_m_per_N", "heat_transfer_W_m2K", "friction_temperature.mu_slope_per_K"} <= set(free)


def test_a_partner_found_only_beside_a_freely_refitted_spline_is_not_named():
    """Two-effect campaign 23 (a power-law creep and a friction fade above 110 °C, one direction, 4 tests, another
    drum radius): a modulus change beside the re-formed creep won the screens when each screen refitted the spline
    too, and was named beside the creep.  With the spline held in the screens no second effect earns its place: the
    answer is "none, structure remains" with both true effects as the closest."""
    from tests.uncertainty.band_questions import two_effect_data
    hidden, *_, data, _ = two_effect_data(23)
    assert set(hidden) == {"creep_power_law", "friction_fade_above"}
    d = diagnose(data)
    assert d.verdict == "none" and d.remaining_structure, d.summary()
    assert {e for a in d.alternatives for e in a["effects"]} == {"lining_creep", "friction_temperature"}


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_logarithmic_cable_creep_on_a_dense_log_is_the_cable_alone(seed):
    """A cable creep with no end value (u_6 − 1.2 µm·ln(1 + t/120 s)), 3 s samples, one direction, 8 hand forces: the
    cable's catalogue form (exponential) leaves a misfit, and its flexible form must lose displacement as the
    cable does — as a factor on u_6 it was a proportional loss, which the catalogue cable beside a lining creep beat
    on held-out tests (named as a pair, or "none" with both as alternatives)."""
    import tests.identify.bench_generator as gen
    with pytest.MonkeyPatch.context() as m:
        m.setitem(gen.SAMPLING, "3s", 3.0)
        data = generate(["cable_log"], sampling="3s", seed=seed, directions=("uphill",),
                        forces=np.linspace(170.0, 350.0, 8))
    d = diagnose(data)
    assert d.verdict == "cable_relaxation" and [e["effect"] for e in d.effects] == ["cable_relaxation"], d.summary()


def test_a_second_effect_is_sought_beside_a_partial_first_with_the_drums_departures_freed():
    """Beside a first effect whose shape-free form clears the structure (form "partial") a second one is named on
    its own evidence: a radiating drum beside a power-law creep (two-effect band campaign 22, paper drum, 1-min),
    where the creep's spline leaves the temperature law's misfit below the structure tests.  A radial contraction
    that passes beside a sigmoid modulus drop's spline only while the thicker lining of its drum is held (held-out
    campaign 225, one hidden effect) is not named: with the drum's departures freed it is no better."""
    from tests.identify.heldout_names import campaign
    from tests.uncertainty.band_questions import two_effect_data
    d = diagnose(two_effect_data(22)[5])
    assert [(e["effect"], e["form"]) for e in d.effects] == [("lining_creep", "partial"), ("radiation_cooling", "exact")]
    step = next(s for s in d.steps if s.get("step") in ("beside the partial first", "beside the re-formed first"))
    assert step["effect"] == "radiation_cooling" and step["delta_bic"] < -10 and step["heldout"]["passes"]
    d = diagnose(campaign(225)[1])
    assert [e["effect"] for e in d.effects] == ["modulus_temperature"] and d.effects[0]["form"] == "partial"


def test_a_power_law_creep_written_as_two_terms_is_no_pair_but_a_true_cable_beside_a_creep_is():
    """Held-out campaign 670 (a lining creep as a power law of time on a drum with its own eq. (24) law, 1-min):
    an exponential creep and a cable relaxation together wrote the power law, and a spline of time on four tests
    predicts held-out tests worse than the two — the cable was named as a partner.  Beside the creep with a second
    term of its own law, the cable adds nothing: the creep is named, the pair flagged as what the data cannot tell
    from it.  The other side, 10 seeds of a true
    exponential creep beside a true cable relaxation (1- and 5-min, six drums, 2–4 forces): the pair stays named
    wherever it was before the rule (8 of 10; the other two name the creep alone either way)."""
    from tests.identify.heldout_names import campaign
    hidden, data = campaign(670)
    assert hidden == "creep_power_law"
    d = diagnose(data)
    assert [e["effect"] for e in d.effects] == ["lining_creep"], d.verdict
    assert any("second term of its own law" in e for e in d.evidence)
    assert any(set(a["effects"]) == {"lining_creep", "cable_relaxation"} for a in d.alternatives)   # "or" the pair
    pairs = 0
    for seed in range(100, 110):
        rng = np.random.default_rng(seed)
        lo = rng.uniform(150, 220)
        drums = [{}] + list(OTHER_DRUMS.values())
        g = diagnose(generate(["creep_exponential", "cable_exponential"], sampling=("1min", "5min")[seed % 2],
                              seed=seed, drum=drums[seed % len(drums)], mu=rng.uniform(0.3, 0.45),
                              h=rng.uniform(25, 45), forces=np.linspace(lo, lo + rng.uniform(120, 200),
                                                                        int(rng.integers(2, 5)))))
        named = {e["effect"] for e in g.effects}
        assert named <= {"lining_creep", "cable_relaxation"}, (seed, named)
        pairs += named == {"lining_creep", "cable_relaxation"}
    assert pairs >= 8, pairs


def test_an_effect_found_beside_a_re_formed_first_is_asked_again_with_the_drums_departures_freed():
    """Held-out campaign 693 (a sigmoid lining-modulus drop on a drum with a thicker, softer lining, 5-min, both
    directions): the bare drum could not identify the arm ratio and held the gap.  The creep picked beside the
    friction law is no better than the friction re-formed, and beside that spline an installation gap lowered BIC
    and predicted held-out tests better — standing in for the drum's departures: with them freed in both fits it
    does not, and no second effect is named."""
    from tests.identify.heldout_names import campaign
    hidden, data = campaign(693)
    assert hidden == "modulus_sigmoid"
    d = diagnose(data)
    assert len(d.effects) == 1 and d.effects[0]["effect"] in {"friction_temperature", "modulus_temperature"}, d.verdict
    assert not any(s.get("step") == "beside the re-formed first" for s in d.steps)



def test_a_second_effect_in_another_channel_is_sought_beside_a_re_formed_first_that_leaves_no_structure():
    """Two-effect band campaign 193 (an exponential lining creep and a radiating drum, 1-min logs,
    another drum, 8 tests): the catalogue creep beside radiation loses to the creep re-formed, a spline of time that
    also takes the torque the radiating drum's cooling changes, although radiation fits the drum temperature that
    no torque hook reaches.  Beside the re-formed creep (which leaves no structure) radiation still lowers BIC and
    predicts held-out tests better: both are named, on that evidence."""
    from tests.uncertainty.band_questions import two_effect_data
    effects, *_, data, _ = two_effect_data(193)
    assert sorted(effects) == ["creep_exponential", "radiation"]
    d = diagnose(data)
    assert [e["effect"] for e in d.effects] == ["lining_creep", "radiation_cooling"], d.verdict
    own = next(s for s in d.steps if s.get("step") == "own evidence")
    assert not own["kept"]                                   # the pair alone is no better than the creep re-formed
    step = next(s for s in d.steps if s.get("step") == "beside the re-formed first")
    assert step["effect"] == "radiation_cooling" and step["delta_bic"] < -10 and step["heldout"]["passes"]


def _unsure_case(elpd: float, se: float, names=("modulus_temperature", "friction_temperature")):
    from types import SimpleNamespace
    from rollaway.identify.partner import unsure_second
    reform = SimpleNamespace(jacobian=[[1.0]])
    steps = [{"step": "beside the re-formed first", "first": "modulus_temperature", "effect": "friction_temperature",
              "delta_bic": -22.3, "reform": reform,
              "heldout": {"heldout_elpd": elpd, "heldout_se": se, "better_tests": 6, "tests": 8}}]
    verdict = SimpleNamespace(model=SimpleNamespace(effects=[SimpleNamespace(name=n) for n in names]))
    return unsure_second(steps), verdict, reform


def test_a_second_effect_within_two_standard_errors_leaves_the_first_alone_flagged(monkeypatch):
    """A second named beside the first re-formed on a held-out gain of 1.4 standard errors: the first re-formed
    alone is named beside the verdict (its re-formed fit in the bands); at 2.1 standard errors, with the rivals
    full, or where the verdict no longer holds that pair, nothing is added."""
    import rollaway.identify.separating_test as st
    monkeypatch.setattr(st, "tell_apart", lambda *a, **k: {"words": "a test"})
    rule, verdict, reform = _unsure_case(104.2, 75.9)
    got = rule(None, None, verdict, [], {}, 8.0, 1.0, [])
    assert [a["effects"] for a in got] == [["modulus_temperature"]] and got[0]["fit"] is reform
    assert got[0]["delta_bic"] == pytest.approx(22.3) and got[0]["heldout_elpd"] == pytest.approx(-104.2)
    rule, verdict, _ = _unsure_case(160.0, 75.9)
    assert rule(None, None, verdict, [], {}, 8.0, 1.0, []) == []
    rule, verdict, _ = _unsure_case(104.2, 75.9)
    full = [{"effects": ["a"]}, {"effects": ["b"]}]
    assert rule(None, None, verdict, [], {}, 8.0, 1.0, full) == full
    rule, verdict, _ = _unsure_case(104.2, 75.9, names=("modulus_temperature", "lining_creep"))
    assert rule(None, None, verdict, [], {}, 8.0, 1.0, []) == []


def test_a_friction_change_named_beside_a_gap_s_modulus_drop_is_flagged():
    """Two-effect band campaign 339: a sigmoid modulus drop on a drum with an installation gap (1-min, both
    directions).  Beside the modulus law re-formed a friction change lowers BIC by 22 and predicts held-out tests
    better by 1.4 standard errors: it is named, with the modulus law alone (re-formed) beside it — before, the
    friction change was a false name with nothing flagged."""
    from tests.identify.heldout_names import judge_two
    from tests.uncertainty.band_questions import two_effect_data
    effects, *_, data, _ = two_effect_data(339)
    d = diagnose(data)
    got = judge_two([str(e) for e in effects], d)
    assert not got["false_unflagged"] and ["modulus_temperature"] in got["alternatives"], d.summary()
